// Scene 14: per-pixel Phong, textured, with nrm and pow.
//   t0 texture coordinates, t1 normal, t2 vector to the light, t3 vector to the eye
//   c1 light colour, c2 ambient colour
ps_2_0
dcl t0.xy
dcl t1
dcl t2
dcl t3
dcl_2d s0
def c0, 0.0, 1.0, 32.0, 0.0
texld r0, t0, s0
nrm r1.xyz, t1
nrm r2.xyz, t2
nrm r3.xyz, t3
dp3_sat r4.x, r1, r2
add r5.xyz, r2, r3
nrm r6.xyz, r5
dp3_sat r4.y, r1, r6
pow r4.z, r4.y, c0.z
mad r7.xyz, r4.x, c1, c2
mul r7.xyz, r7, r0
mad r7.xyz, r4.z, c1, r7
mov r7.w, r0.w
mov oC0, r7
