// Comment blocks as `sm2 dis` prints them (a compiler's constant table, another FOURCC, an
// empty block), with fxc's statement order: def before dcl.
ps_2_0
comment 0x42415443, 0x0000001c, 0x0000004f, 0xffff0200, 0x00000001, 0x0000001c, 0x00008100, 0x00000048,
        0x00000030, 0x00000002, 0x00020001, 0x00000038, 0x00000000, 0x6f6c6f43, 0xabab0072, 0x00030001,
        0x00040001, 0x00000001, 0x00000000, 0x325f7370, 0x4d00305f, 0x6f726369, 0x74666f73, 0x29522820,
        0x534c4820, 0x6853204c, 0x72656461, 0x6d6f4320, 0x656c6970, 0x2e392072, 0x392e3932, 0x332e3235,
        0x00313131
comment 0x53455250, 0xffffffff, 0x0
comment
def c1, 0.5, 1, 0, 0
dcl t0.xy
dcl_2d s0
texld r0, t0, s0
mul r0, r0, c0
mov oC0, r0
