// 000 Program 3.3 (l.3203): per-pixel Phong, entry PShader. Compiles as printed but for the
// output: `(float3)pout.col = col` (a cast is no l-value) as a float4 constructor with the
// listing's `pout.col.w = 0.0f`. pow(x, n) of a negative x: D3D9's pow takes |x|, the max(0, ...)
// outside it then changes nothing (scenes.md); max(0, dot) inside the pow is meant.
float3 light_col_diff; // skladowa rozproszona
float3 light_col_spec; // skl. zwierciadlana
float light_pn;        // wsp. gladkosci

float3 scol; // kolor powierzchni obiektu

struct T_PIN // dane wejsciowe
{
    float3 eye : TEXCOORD0;   // kierunek patrzenia obserwatora
    float3 light : TEXCOORD1; // kier. padania swiatla
    float3 n : TEXCOORD2;     // wektor normalny |n|!=1
};

struct T_POUT // dane wyjsciowe
{
    float4 col : COLOR0; // kolor
};

T_POUT PShader(T_PIN pin) // mikroprogram dla pikseli
{
    T_POUT pout;
    float3 eye, eye_rfl, light, n, col;
    float lp;

    // normalizacja wektorow po interpolacji
    eye = normalize(pin.eye);
    light = normalize(pin.light);
    n = normalize(pin.n);

    eye_rfl = reflect(eye, n); // odbicie wektora wzgledem n

    // skladowa rozproszona
    lp = max(0, dot(n, light));
    col = light_col_diff * lp;

    // skladowa zwierciadlana
    lp = pow(max(0, dot(eye_rfl, light)), light_pn);
    col += light_col_spec * lp;

    col *= scol; // kolor powierzchni

    pout.col = float4(col, 0.0f);

    return pout;
};
