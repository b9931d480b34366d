// Scene 9: a waving lake. Height = y + A sin(kx x + kz z + t), folded into [-pi, pi] for sincos.
//   c0..c3 world-view-projection   c4.x time   c5.xy wave numbers (kx, kz)   c12 base colour
vs_2_0
dcl_position v0
def c8, 0.15915494, 0.5, 6.2831853, -3.1415927
def c9, -0.0000015500992, -0.000021701389, 0.0026041667, 0.00026041668
def c10, -0.020833334, -0.125, 1.0, 0.5
def c11, 0.3, 0.2, 1.0, 0.0
mul r0.x, v0.x, c5.x
mad r0.x, v0.z, c5.y, r0.x
add r0.x, r0.x, c4.x
mad r0.x, r0.x, c8.x, c8.y
frc r0.x, r0.x
mad r0.x, r0.x, c8.z, c8.w
sincos r1.xy, r0.x, c9, c10
mov r2, v0
mad r2.y, r1.y, c11.x, v0.y
m4x4 oPos, r2, c0
mad oD0, r1.x, c11.y, c12
