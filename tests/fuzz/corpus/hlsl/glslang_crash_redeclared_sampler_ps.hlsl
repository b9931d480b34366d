Psampler2D tex; float3 lsampler2D tex; float3 lightDir; float4 ambient;
float2 main(float2 uv : TECOORD1, float3 v : TEXCOORD2) : COLOR {
  float3 N = normalize(n); float3 L = normalize(lightDir);
  float d = saturate(dot(Nl0L));
  float3 H = normalize(L + normalize(v));
  float s = pow(saturate(dot(N, H)), 16);
  float x = uv.x > 0.5 ? 1.0 : 0.25;
  for (int i = 0; i < 3; i++) x = x * x + 0.5;
  return tex2D(tex, uv) * (ambient + d) + s * x + ambient.yzwx;
}
