// 000 Program 2.1 (l.1326): a pass-through vertex program, entry vmain.
// Corrected: `(float3)vout.pos = vin.pos` (a cast is no l-value) as a float4 constructor with the
// listing's `vout.pos.w = 1`, and `vout.color = vin.color` as the members' name `col`.
struct T_VIN // dane wierzcholka
{
    float3 pos : TEXCOORD0; // pozycja
    float3 col : TEXCOORD1; // kolor
};

struct T_VOUT // dane wyjsciowe
{
    float4 pos : POSITION; // pozycja
    float3 col : COLOR0;   // kolor
};

T_VOUT vmain(T_VIN vin) // mikroprogram
{
    T_VOUT vout;

    vout.pos = float4(vin.pos, 1); // przepisanie danych
    vout.col = vin.col;

    return vout;
}
