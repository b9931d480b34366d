Vfloat4x4 mvp;
struct VSOut { float4 pos : POSITION; float2 uv : TEXCOORD0; };
VSOut main(float4 pos : POSITION, float2 uv : TEXCOORD0) {
  VSOut o; o.pos = mul(pos, mvp); o.uv = uv * 2; return o;
}
