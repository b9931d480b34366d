// 002 listing 4.2 (l.686): the G-buffer's normal from a tangent-space normal map and the depth
// z/w, entry main. The listing is a fragment (its letters spaced out by the PDF extraction); the
// declarations around it (the input struct, the sampler, the output struct with the listing's
// Normal and Depth members) are written here as the listing uses them. Compiles as printed.
sampler2D NormalSampler : register(s0);

struct VertexShaderOutput
{
    float2 TexCoord : TEXCOORD0;
    float3 Normal : TEXCOORD1;
    float3 Tangent : TEXCOORD2;
    float3 Binormal : TEXCOORD3;
    float2 Depth : TEXCOORD4;
};

struct PixelShaderOutput
{
    float4 Normal : COLOR0;
    float4 Depth : COLOR1;
};

PixelShaderOutput main(VertexShaderOutput input)
{
    PixelShaderOutput output;
    float3 sample = tex2D(NormalSampler, input.TexCoord).rgb;
    float3 normalBump = sample * 2 - 1;
    float3 normal = normalize(input.Normal);
    float3 tangent = normalize(input.Tangent) * normalBump.x;
    float3 binormal = normalize(input.Binormal) * normalBump.y;
    normal = normalize(normal + tangent + binormal);
    output.Normal = float4(normal * 0.5 + 0.5, 1);
    output.Depth = input.Depth.x / input.Depth.y;
    return output;
}
