ps_2_0
dcl t0.xy
dcl t1
dcl v0
dcl_2d s0
dcl_cube s1
def c0, 0.5, 1.0, 0.0, 0.25
texld r0, t0, s0
texldp_pp r1, t1, s1
mul_pp r0, r0, v0
lrp_sat r2, c0.x, r0, r1
mov r2.w, c0.y
mov oC0, r2
