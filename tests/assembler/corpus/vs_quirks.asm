// vs_2_0 forms Wine encodes without validating.
vs_2_0
dcl_position v0
mov a0.x, v0.x
mov_sat r0, v0
frc_sat r1, v0
call l2047
ret
label l2047
mov oFog.x, r0.x
mov oPts.y, r0
mov r1, c2047
ret
