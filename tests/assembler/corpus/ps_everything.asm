// Every ps_2_0 instruction and operand form the assembler writes.
ps_2_0
dcl v0
dcl v1.xyz
dcl t0.xy
dcl_pp t1
dcl_centroid t2.xyz
dcl t3
dcl t4.x
dcl t5
dcl t6
dcl t7.rgba
dcl s0
dcl_2d s1
dcl_cube s2
dcl_volume s3
dcl_1d s15
def c0, 0.5, 1.0, 0.0, 0.25
def c1, -1.5500992e-6, -2.1701389e-5, 0.0026041667, 0.00026041668
def c2, -0.020833334, -0.125, 1.0, 0.5
def c31, 0.001, -100000, 7.5f, -3.25
texld r0, t0, s1
texldp_pp r1, t3, s2
texldb r2, t1, s3
texld_pp r3, r0, s0
texkill t4
texkill r0
mov r4, v0
add_pp r4, r4, v1
sub_sat r5, r4, c0.x
mad r5, r4, c0.y, -r3
mul r6.xy, r5, c1
rcp r6.z, r5.x
rsq r6.w, r5.y
dp3 r7, r5, c2
dp4 r7.x, r5, c2
min r8, r7, r6
max r8, r7, r6
exp r9, r8.x
log r9, r8.w
lrp r10, c0.w, r9, r8
frc r10, r9
m4x4 r11, r10, c3
m4x3 r11.xyz, r10, c7
m3x4 r1, r10, c10
m3x3 r1.xyz, r10, c14
m3x2 r1.xy, r10, c17
pow r2, r1.x, c0.y
crs r2.xyz, r1, r0
abs r3, -r2
nrm_pp r3, r2
sincos r4.xy, r3.x, c1, c2
sincos r4.y, r3.w
cmp r5, r4, c0, -c0
dp2add r6, r5, r4, c0.x
mov r0.rgb, r1.bgra
mov_sat r1, r0.yzxw
mov r2, r0.zxyw
mov r3, r0.wzyx
mov oC0, r0
mov oC1, r1
mov oC2, r2
mov oC3, r3
mov oDepth, r0.x
