// Forms Wine's assembler encodes although the documents forbid them (spec README item 3).
ps_2_0
dcl t0
defi i0, 1, 2, 3, 4
defb b0, true
expp r12, t0.x
logp r31, t0.y
texkill t0.xyz
mov oC0, r12.x
add_sat oC1, r31, t0
mov oDepth.x, r12
mov r0, i0
mov r1, b0
