Psampler2D tex; float3 lightDir; float4 ambient;
float4 main(float2 uv : TEXCOORD0, float4 n : TEXCOORD1, float3 v : TEXCOORD2) :Psampler2D tex; float3 lightDir; float4 ambient;
float2 main(float2 u COv :L