// 002 listings 4.3 and 4.4 (l.945-968): the world position rebuilt from the depth texture with
// D3D9's half-pixel convention and the normal read back from the G-buffer, in a light volume's
// pixel shader, entry main. The listings are fragments; the declarations around them and the
// output (here N.L for a light at LightPosition, so that every value is used) are written as the
// listings use them. Corrected: `float depth = tex2D(DepthSampler, texCoord)` assigns a float4 to
// a float (the depth is the texel's .r); mul(csPosition, ViewProjectionInverse) with the matrix
// row_major, as the stream sets it.
sampler2D DepthSampler : register(s0);
sampler2D NormalSampler : register(s1);
row_major float4x4 ViewProjectionInverse : register(c0);
float2 PixelSize : register(c4);
float3 LightPosition : register(c5);

float4 main(float4 ViewPosition : TEXCOORD0) : COLOR0
{
    float4 position = ViewPosition;
    float2 csXY = position.xy / position.w;
    float u = (csXY.x + 1 + PixelSize.x) * 0.5;
    float v = (1 - csXY.y + PixelSize.y) * 0.5;
    float2 texCoord = float2(u, v);
    float depth = tex2D(DepthSampler, texCoord).r;
    float4 csPosition = float4(csXY, depth, 1);
    float4 wsPosition = mul(csPosition, ViewProjectionInverse);
    float3 wPosition = wsPosition.xyz / wsPosition.w;

    float3 normal = tex2D(NormalSampler, texCoord).xyz;
    normal = normalize(normal * 2 - 1);

    float3 toLight = normalize(LightPosition - wPosition);
    return float4(saturate(dot(normal, toLight)).xxx, 1);
}
