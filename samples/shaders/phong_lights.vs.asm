// Scene 8: per-vertex Phong with up to 8 point lights in a static loop.
//   c0..c3  world-view-projection       c4..c6  world (rows of a 4x3)
//   c8      eye position (world)        c9      ambient colour
//   c16 + 2k  light k position          c17 + 2k  light k colour
//   i0 = (light count, 16, 2, 0): aL walks c16, c18, ... so c[aL] and c[aL + 1] are light k.
vs_2_0
dcl_position v0
dcl_normal v1
def c10, 0.0, 1.0, 32.0, 0.0
defi i0, 4, 16, 2, 0
m4x4 oPos, v0, c0
m4x3 r0.xyz, v0, c4
m3x3 r1.xyz, v1, c4
nrm r2.xyz, r1
sub r3.xyz, c8, r0
nrm r4.xyz, r3
mov r5, c9
loop aL, i0
sub r6.xyz, c[aL], r0
nrm r7.xyz, r6
dp3 r8.x, r2, r7
max r8.x, r8.x, c10.x
add r9.xyz, r7, r4
nrm r10.xyz, r9
dp3 r8.y, r2, r10
max r8.y, r8.y, c10.x
pow r8.z, r8.y, c10.z
mad r5.xyz, c[aL + 1], r8.x, r5
mad r5.xyz, c[aL + 1], r8.z, r5
endloop
mov oD0, r5
