// The neon light's pixel shader of scenes 26 and 27 (samples/scenes/26_neon_light.sm2cs).
// Beyond ps_2_0's 64 arithmetic slots, so the streams load its bytecode, assembled with
//   sm2 asm samples/scenes/data/deferred_neon_light.ps.asm --max-slots 512 \
//       -o samples/scenes/data/deferred_neon_light.ps.bin
// (an asm<<END heredoc goes through the replayer's assembler, which validates with the
// default ps_2_0 budget whatever --max-slots says).
ps_2_0
// Rebuilding the lit point (002 l.903-924): t0 is the clip-space position of the light
// geometry; at a pixel centre, x/w and y/w are that centre in clip space. D3D9 samples pixels at
// integer coordinates and texels at their centres, so the G-buffer texel of the pixel is at
//   u = (x/w + 1 + 1/W) / 2,  v = (1 - y/w + 1/H) / 2      (c1 = (0.5 + 0.5/W, 0.5 + 0.5/H)).
// The world position is inverse(view-projection) * (x/w, y/w, depth, 1), divided by its w.
// The neon light (002 l.1224-1451), beyond ps_2_0's 64 arithmetic slots (a ps_2_x-size limit:
// 26_neon_light.options). c10 (A, |B - A|), c11 (segment direction, 1/radius), c12 (colour *
// intensity, hasSpecular), c13 (Ri, the barn doors' reference direction), c14 (X1 distance
// where the barn doors start, X2 = 6 blades, 2 X3 (X3 transmittance), X4 radius (X4 softness)),
// c15 (I specular intensity, 128/8, 4, -3).
//  diffuse (l.1290): the closest point of the segment, cp towards it, h = |cp| / radius, the
//    bent normal normalize(N + cp (1 - h^2) / 2), (sat(cp . bent) (1 - h))^2;
//  specular (l.1340): the closest points of the segment and the reflection ray R (clamped to
//    the segment), sat(L . R) sat(1 - (dist / radius)^(1 + tc / radius)), here raised to the
//    material's exponent / 8 and faded by (1 - h) so that it ends at the volume;
//  barn doors (l.1420): cos(6 acos(Ri . cp)) = T6(Ri . cp), the Chebyshev polynomial
//    T3(T2(x)) (ps_2_0 has no acos), bds = sat(2 X3 - T6), applied beyond X1 as
//    bds^(X4 radius / |cp|).
def c2, 0.0001, 0, 0, 0
dcl t0
dcl_2d s1
dcl_2d s2
dcl_2d s3
def c0, 0.5, -0.5, 0, 0
def c3, 1, 0, 0.5, 128
def c9, 2, -1, 0, 0
rcp r0.w, t0.w
mul r0.xy, t0, r0.w
mad r1.xy, r0, c0, c1
mul r0.z, t0.z, r0.w
texld r2, r1, s1
texld r3, r1, s2
texld r4, r1, s3
sub r5, r3.w, c3.z
sub r5.x, r0.z, r4.x
mov r6.xy, r0
mov r6.z, r4.x
mov r6.w, c3.x
m4x4 r7, r6, c4
rcp r7.w, r7.w
mul r7.xyz, r7, r7.w
mad r3.xyz, r3, c9.x, c9.y
nrm r6.xyz, r3
sub r8.xyz, c10, r7
dp3 r9.x, c11, -r8
max r9.x, r9.x, c3.y
min r9.x, r9.x, c10.w
mad r10.xyz, r9.x, c11, r8
dp3 r9.y, r10, r10
rsq r9.z, r9.y
mul r9.w, r9.y, r9.z
mul r10.xyz, r10, r9.z
mad r5.y, -r9.w, c11.w, c3.x
texkill r5
mul_sat r9.x, r9.w, c11.w
mad r9.y, -r9.x, r9.x, c3.x
mul r9.y, r9.y, c3.z
mad r11.xyz, r10, r9.y, r6
nrm r0.xyz, r11
dp3_sat r0.w, r10, r0
add r9.x, c3.x, -r9.x
mul r0.w, r0.w, r9.x
mul r0.w, r0.w, r0.w
sub r1.xyz, c8, r7
nrm r3.xyz, r1
dp3 r1.x, r3, r6
add r1.x, r1.x, r1.x
mad r4.xyz, r6, r1.x, -r3
dp3 r1.x, c11, r4
dp3 r1.y, c11, r8
dp3 r1.z, r4, r8
mad r1.w, -r1.x, r1.x, c3.x
max r1.w, r1.w, c2.x
rcp r1.w, r1.w
mad r3.x, r1.x, r1.z, -r1.y
mul r3.x, r3.x, r1.w
max r3.x, r3.x, c3.y
min r3.x, r3.x, c10.w
mad r11.xyz, r3.x, c11, r8
dp3 r3.y, r4, r11
mad r5.xyz, -r3.y, r4, r11
dp3 r5.w, r5, r5
rsq r5.w, r5.w
rcp r5.w, r5.w
mul r5.w, r5.w, c11.w
mad r1.w, r3.y, c11.w, c3.x
pow r3.z, r5.w, r1.w
add_sat r3.z, c3.x, -r3.z
nrm r5.xyz, r11
dp3_sat r3.w, r5, r4
mul r3.z, r3.z, r3.w
mul r1.w, r2.w, c15.y
pow r3.z, r3.z, r1.w
mul r3.z, r3.z, r9.x
dp3 r1.x, c13, r10
mul r1.y, r1.x, r1.x
mad r1.y, r1.y, c9.x, c9.y
mul r1.z, r1.y, r1.y
mad r1.z, r1.z, c15.z, c15.w
mul r1.z, r1.z, r1.y
add_sat r1.z, c14.z, -r1.z
mul r5.w, r9.z, c14.w
pow r1.z, r1.z, r5.w
sub r1.w, c14.x, r9.w
cmp r1.z, r1.w, c3.x, r1.z
mul r0.w, r0.w, r1.z
mul r3.z, r3.z, r1.z
mul r0.xyz, r0.w, c12
mul r3.z, r3.z, c15.x
mul r3.z, r3.z, c12.w
mul r4.xyz, r3.z, c12
mul r4.xyz, r4, r2
mov r0.w, c3.y
mov r4.w, c3.y
mov oC0, r0
mov oC1, r4
