vs_2_0
dcl_position v0
dcl_normal v1
dcl_texcoord0 v2
def c8, 1.0, 0.0, 0.5, 2.0
def c9, -0.0000015500992, -0.000021701389, 0.0026041667, 0.00026041668
def c10, -0.020833334, -0.125, 1.0, 0.5
m4x4 oPos, v0, c0
dp3 r0.x, v1, c4
max r0.x, r0.x, c8.y
mova a0.x, c8.w
mul oD0, r0.x, c[a0.x + 5]
sincos r1.xy, v2.x, c9, c10
mov oT0.xy, r1
mov oFog, c8.x
