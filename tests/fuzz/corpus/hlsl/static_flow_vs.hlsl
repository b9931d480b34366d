Vbool a;
bool b;
int n;
float4 k;
float4 main(float4 pos : POSITION, out float4 col : COLOR0) : POSITION {
  float4 acc = pos;
  if (!a) {
    acc = acc * 2;
    if (b) acc += k;
  }
  for (int i = 0; i < n; i++) {
    if (b) acc += k; else acc -= 1;
  }
  col = a ? acc : -acc;
  return pos;
}
