// A 64-slot arithmetic pixel shader (the ps_2_0 limit), for benchmarks: every kind of ALU
// instruction, no texture reads. A mov, two 25-slot blocks and a 13-slot tail.
ps_2_0
dcl t0
dcl t1
def c0, 0.5, 1.5, 2.0, 0.25
def c1, 0.75, 0.125, 1.0, -0.5
mov r11, t0
mul r0, r11, c0
mad r1, t1, c0.y, r0
add r2, r0, r1
dp3 r3.x, r2, r1
rsq r3.y, r3.x
rcp r3.z, r3.y
mul r4, r2, r3.y
mad r5, r4, r3.z, c0
max r5, r5, c0.w
min r5, r5, c0.z
nrm r6.xyz, r5
dp3_sat r7.x, r6, r1
pow r7.y, r7.x, c0.z
exp r7.z, r7.x
log r7.w, r7.y
cmp r8, r7, r5, r4
lrp r9, r7.x, r8, r2
frc r10, r9
abs r11, r10
mad r11, r11, c0.x, r9
mul r0, r11, c0
mad r1, t1, c0.y, r0
add r2, r0, r1
dp3 r3.x, r2, r1
rsq r3.y, r3.x
rcp r3.z, r3.y
mul r4, r2, r3.y
mad r5, r4, r3.z, c0
max r5, r5, c0.w
min r5, r5, c0.z
nrm r6.xyz, r5
dp3_sat r7.x, r6, r1
pow r7.y, r7.x, c0.z
exp r7.z, r7.x
log r7.w, r7.y
cmp r8, r7, r5, r4
lrp r9, r7.x, r8, r2
frc r10, r9
abs r11, r10
mad r11, r11, c0.x, r9
mul r0, r11, c1
add r0, r0, r9
mad r0, r0, c1.x, r8
dp4 r1.x, r0, r11
mul r1.y, r1.x, c1.y
add r1.z, r1.y, c1.z
max r1.w, r1.z, c1.w
mul r2, r0, r1
mad r2, r2, c1, r0
add r2, r2, r7
mul_sat r2, r2, c1.y
add r2.xyz, r2, r6
mov oC0, r2
