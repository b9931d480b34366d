Pbool useRed;
float4 main(float2 uv : TEXCOORD0) : COLOR {
  float4 c = float4(uv, 0, 1);
  if (useRed) c.x = 1;
  return c;
}
