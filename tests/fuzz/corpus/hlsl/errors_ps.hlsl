Pfloat4 main(float2 uv : TEXCOORD0) : COLOR {
  if (uv.x < 0.5) discard;
  return undefined_name;
}
