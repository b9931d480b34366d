Vfloat time; row_major float4x4 m;
float4 main(float4 p : POSITION, out float4 c : COLOR0) : POSITION {
  float h = sin(p.x * 2 + time) * 0.5 + cos(p.z + time) * 0.25;
  c = mul(m, p) * (h >= 0 ? 1 : 0.5);
  return float4(p.x, h, p.z, 1);
}
