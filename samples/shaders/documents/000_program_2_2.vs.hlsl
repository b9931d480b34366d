// 000 Program 2.2 (l.1492): the transform by mxLocalToView, entry vmain.
// Corrected: `(float3)wpos = vin.pos` (a cast is no l-value) as a float4 constructor.
float4x4 mxLocalToView; // macierz transformacji

struct T_VIN // dane wierzcholka
{
    float3 pos : TEXCOORD0; // pozycja
};

struct T_VOUT // dane wyjsciowe
{
    float4 pos : POSITION; // pozycja
};

T_VOUT vmain(T_VIN vin)
{
    T_VOUT vout;
    float4 wpos;

    wpos = float4(vin.pos, 1);

    // transformcja wierzcholka
    vout.pos = mul(mxLocalToView, wpos);

    return vout;
}
