vs_2_0
dcl_position v0
defb b0, true
defi i0, 4, 0, 1, 0
mov r0, v0
loop aL, i0
add r0, r0, c10[aL]
endloop
if b0
call l1
endif
mov oPos, r0
ret
label l1
mul r0, r0, c2
ret
