// 000 Program 3.5 (l.3346): textured per-pixel Phong with a normalization cube map (entry
// PShader). Corrected: the listing's cube map stores 1/|d| and multiplies, texCUBE(nmap, d) * d,
// which does not normalize (every d along one direction reads the same texel; scenes.md): the
// cube map stores the unit direction itself (a float cube texture), so texCUBE(nmap, d).xyz is
// the normalized d; `col *= tex2D(tex, pin.uv)` takes the texel's .xyz; `(float3)pout.col = col`
// (a cast is no l-value) as a float4 constructor; max(0, dot) inside the pow (see Program 3.3).
float3 light_col_diff; // skladowa rozproszona
float3 light_col_spec; // skl. zwierciadlana
float light_pn;        // wsp. gladkosci

sampler2D tex;    // textura dwuwymiarowa
samplerCUBE nmap; // textura normalizujaca

struct T_PIN
{
    float3 eye : TEXCOORD0;   // kier. patrzenia obserwatora
    float3 light : TEXCOORD1; // kier. padania swiatla
    float3 n : TEXCOORD2;     // wektor normalny |n|!=1
    float2 uv : TEXCOORD3;    // wsp. tekstury
};

struct T_POUT // dane wyjsciowe
{
    float4 col : COLOR0; // kolor
};

T_POUT PShader(T_PIN pin) // mikroprogram dla pikseli
{
    T_POUT pout;
    float3 eye, eye_rfl, light, n, col, tcol;
    float lp;

    // normalizacja wektorow po interpolacji
    eye = texCUBE(nmap, pin.eye).xyz;
    light = texCUBE(nmap, pin.light).xyz;
    n = texCUBE(nmap, pin.n).xyz;

    eye_rfl = reflect(eye, n); // odbicie wektora wzgledem n

    // skladowa rozproszona
    lp = max(0, dot(n, light));
    col = light_col_diff * lp;

    // skladowa zwierciadlana
    lp = pow(max(0, dot(eye_rfl, light)), light_pn);
    col += light_col_spec * lp;

    col *= tex2D(tex, pin.uv).xyz; // kolor powierzchni

    pout.col = float4(col, 0.0f);

    return pout;
};
