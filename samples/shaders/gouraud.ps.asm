// Scene 1 (Gouraud triangle): the interpolated colour is the pixel colour.
ps_2_0
dcl v0
mov oC0, v0
