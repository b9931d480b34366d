// 000 Program 3.1 (l.3053): Gouraud shading, the interpolated colour, entry PShader. Compiles as
// printed.
struct T_PIN // dane interpolowane miedzy wierzcholkami
{
    float4 col : COLOR0; // kolor wejsciowy
};

struct T_POUT // dane wyjsciowe
{
    float4 col: COLOR0; // kolor wynikowy
};

T_POUT PShader(T_PIN pin) // mikroprogram
{
    T_POUT pout;

    pout.col = pin.col; // przepisanie danych

    return pout;
}
