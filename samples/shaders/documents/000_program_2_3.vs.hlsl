// 000 Program 2.3 (l.1598): skinning with three bones, entry vmain.
// Corrected: mul(bones[i], vin.pos) multiplies a 3x4 matrix by a float3 (a float4 with w = 1 is
// meant); `(float3)pos2 = ...` (a cast is no l-value) as a float4 constructor with the listing's
// `pos2.w = 1.0f`.
float3x4 bones[3]; // macierze kosci
float4x4 mx_Global2View;

struct T_VIN // dane wierzcholka
{
    float3 pos : TEXCOORD0; // pozycja
    float w[2] : TEXCOORD1; // wagi
};

struct T_VOUT // dane wyjsciowe
{
    float4 pos : POSITION;
};

T_VOUT vmain(T_VIN vin) // mikroprogram
{
    T_VOUT vout;
    float3 p1, p2, p3;
    float4 pos2;

    // 3 pozycje wierzcholka
    p1 = mul(bones[0], float4(vin.pos, 1));
    p2 = mul(bones[1], float4(vin.pos, 1));
    p3 = mul(bones[2], float4(vin.pos, 1));

    // wagowanie
    pos2 = float4(vin.w[0] * p1 + vin.w[1] * p2 + (1 - vin.w[0] - vin.w[1]) * p3, 1.0f);

    // transformacja
    vout.pos = mul(mx_Global2View, pos2);

    return vout;
}
