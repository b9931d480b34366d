// Every vs_2_0 instruction and operand form the assembler writes.
vs_2_0
dcl_position v0
dcl_blendweight v1
dcl_blendindices v2.xyz
dcl_normal v3
dcl_psize v4.x
dcl_texcoord0 v5.xy
dcl_texcoord7 v6
dcl_tangent v7
dcl_binormal1 v8
dcl_tessfactor v9.x
dcl_positiont v10
dcl_color0 v11
dcl_color1 v12
dcl_fog v13.x
dcl_depth v14.x
dcl_sample v15
def c0, 0.0, 0.5, 1.0, 2.0
def c1, -1.5500992e-6, -2.1701389e-5, 0.0026041667, 0.00026041668
def c2, -0.020833334, -0.125, 1.0, 0.5
def c3, -0.0, 1024, .25, 3.
def c4, 0.1, 0.2, 0.3, 123456.789
defb b0, true
defb b1, false
defi i0, 4, 0, 1, 0
defi i1, -1, 255, -128, 127
mov r0, v0
add r1, r0, -c0.x
sub r2.xyz, r1.zyx, c1
mad r3, r0, c0.yyyy, r1
mul_sat r4.xw, r0.wzyx, c2
rcp r5.x, r0.w
rsq r5.y, r0.z
dp3 r6.x, v3, c3
dp4 r6.y, v0, c4
min r7, r0, r1
max r7, r7, -r1
slt r8, r0, c0.z
sge r8, r0, c0.z
exp r9.x, r0.x
log r9.y, r0.y
lit r10, r0
dst r10, r0, r1
lrp r11, r0, r1, r2
frc r11.xy, r0
m4x4 r0, v0, c10
m4x3 r0.xyz, v0, c14
m3x4 r1, v3, c17
m3x3 r1.xyz, v3, c21
m3x2 r1.xy, v3, c24
pow r2, r0.x, r1.y
crs r2.xyz, r0, r1
sgn r3, r0, r4, r5
abs r3, -r0
nrm r4, r0
sincos r5.xy, r0.x, c1, c2
sincos r5.x, r0.y, c1, c2
expp r6, r0.x
logp r6.w, r0.w
mova a0.x, r0.x
mova a0.yzw, r0
mov r0, c[a0.x]
mov r0, c[a0.y + 5]
mov r0, c12[a0.z]
mov r0, -c[a0.w + 100].wzyx
mov r0, c[a0 + 3]
rep i0
add r0, r0, c0
endrep
loop aL, i1
mad r0, r0, c[aL + 30], c[aL]
endloop
if b0
mov r1, r0
else
mov r1, -r0
endif
if !b1
call l1
endif
callnz l2, b0
callnz l2, !b1
mov oPos, r0
mov oFog, r0.x
mov oPts, r0.y
mov oD0, r1
mov oD1.xyz, r2
mov oT0, r3
mov oT7.zw, r4
nop
ret
label l1
mov r0, c0
ret
label l2
ret
