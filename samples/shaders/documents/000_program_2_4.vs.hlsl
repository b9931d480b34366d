// 000 Program 2.4 (l.1687): per-vertex Phong lighting over n_lights lights, entry vmain.
// Corrected: `(float3)pos = vin.pos` (a cast is no l-value) as a float4 constructor with the
// listing's w = 1; `vout.col = (float3)pos` with pos = {0, 0, 0, 1} is written as the zero it is.
struct T_LIGHT // dane swiatla
{
    float3 pos;      // pozycja swiatla
    float3 col_diff; // skladowa rozproszona
    float3 col_spec; // skl. zwierciadlana
    float pn;        // wsp. gladkosci
};

int n_lights;      // ilosc swiatel
T_LIGHT lights[8]; // swiatla (maks. 8)

float4x4 mxLocalToView; // macierz transformacji
float3 eye_pos;         // pozycja obserwatora

struct T_VIN // dane wierzcholka
{
    float3 pos : TEXCOORD0; // pozycja
    float3 n : TEXCOORD1;   // wektor normalny
    float3 col : TEXCOORD2; // kolor
};

struct T_VOUT // dane wyjsciowe
{
    float4 pos : POSITION; // pozycja
    float3 col : COLOR0;   // kolor
};

T_VOUT vmain(T_VIN vin) // mikroprogram
{
    T_VOUT vout;
    int i;
    float3 eye, eye_rfl, light;
    float lp;

    vout.col = 0;
    eye = normalize(eye_pos - vin.pos);
    eye_rfl = reflect(eye, vin.n);

    // obliczenie natezenia swiatla
    for (i = 0; i < n_lights; i++)
    {
        light = normalize(lights[i].pos - vin.pos);

        // skladowa rozproszona
        lp = max(0, dot(vin.n, light));
        vout.col += lights[i].col_diff * lp;

        // skladowa zwierciadlana
        lp = max(0, pow(dot(eye_rfl, light), lights[i].pn));
        vout.col += lights[i].col_spec * lp;
    }

    // kolor powierzchni
    vout.col *= vin.col;
    // pozycja
    vout.pos = mul(mxLocalToView, float4(vin.pos, 1));

    return vout;
}
