// 000 Program 3.2 (l.3169): vectors for per-pixel Phong, entry VShader.
// Corrected: `(float3)pos = vin.pos` (a cast is no l-value) as a float4 constructor.
float4x4 mxLocalToView; // macierz transformacji
float3 eye_pos;         // pozycja obserwatora
float3 light_pos;       // pozycja swiatla

struct T_VIN // dane wejsciowe
{
    float3 pos : TEXCOORD0; // pozycja wierzcholka
    float3 n : TEXCOORD1;   // wektor normalny
};

struct T_VOUT // dane wyjsciowe
{
    float4 pos : POSITION;   // pozycja
    float3 eye : TEXCOORD0;  // kierunek patrz. obserwatora
    float3 light : TEXCOORD1; // kierunek padania swiatla
    float3 n : TEXCOORD2;    // wektor normalny
};

T_VOUT VShader(T_VIN vin) // mikroprogram dla wierzcholkow
{
    T_VOUT vout;
    float4 pos = {0, 0, 0, 1};

    pos = float4(vin.pos, 1); // pozycja
    vout.pos = mul(mxLocalToView, pos);

    vout.eye = eye_pos - vin.pos;     // wektor kierunkowy
    vout.light = light_pos - vin.pos; // wektor kierunkowy
    vout.n = vin.n;                   // przepisanie

    return vout;
}
