/*
 * ff_fog_texgen.c - fixed-function fog modes and texture-coordinate generation (no shaders).
 *
 * frame 0, fog: a vertex-coloured ground grid (XYZ|DIFFUSE, 8x16 quads, DrawIndexedPrimitiveUP)
 *   and three upright quads at depths 3, 7 and 12, seen in a 2x4 grid of 128x64 viewports, each
 *   with one fog setup and its own FOGCOLOR: vertex LINEAR, EXP, EXP2, LINEAR with RANGEFOGENABLE,
 *   table LINEAR/EXP/EXP2 under an orthographic projection (fog of the depth in [0, 1]), and table
 *   LINEAR under the perspective projection (D3D9: eye-space w, start/end in camera units).
 * frame 1, texgen: a UV sphere (XYZ|NORMAL|DIFFUSE|SPECULAR|TEX1) in a 3x2 grid of 85x128
 *   viewports, textured from generated coordinates: CAMERASPACENORMAL and CAMERASPACEPOSITION
 *   with COUNT2 texture transforms (scale and offset into [0, 1]), CAMERASPACEREFLECTIONVECTOR
 *   with LOCALVIEWER on and off into a 16x16 cube texture (COUNT3), SPHEREMAP, and the sphere's
 *   own (u, v) projected through COUNT3 | PROJECTED.  Textures: a 16x16 A8R8G8B8 gradient with a
 *   checker in blue (LINEAR, CLAMP) and a cube texture with a differently tinted gradient per face.
 */
#include "sphere.h"

typedef struct { float x, y, z; DWORD color; } ColorVertex;

static void rs(D3DRENDERSTATETYPE s, DWORD v) { CHECK(IDirect3DDevice9_SetRenderState(g_dev, s, v)); }
static void ts(DWORD stage, D3DTEXTURESTAGESTATETYPE t, DWORD v)
{
    CHECK(IDirect3DDevice9_SetTextureStageState(g_dev, stage, t, v));
}

static DWORD gradient(int x, int y, int face)
{
    static const DWORD tint[6] = { 0xff4040, 0x40ff40, 0x4040ff, 0xffff40, 0x40ffff, 0xff40ff };
    DWORD r = x * 16 + 8, g = y * 16 + 8, b = ((x >> 2) ^ (y >> 2)) & 1 ? 0xc0 : 0x20;
    if (face >= 0) {
        DWORD t = tint[face];
        r = (((t >> 16) & 0xff) * (x * 8 + 128)) >> 8;
        g = (((t >> 8) & 0xff) * (y * 8 + 128)) >> 8;
        b = ((t & 0xff) * (255 - x * 8)) >> 8;
    }
    return 0xff000000 | (r << 16) | (g << 8) | b;
}

int main(int argc, char **argv)
{
    IDirect3DVertexBuffer9 *vb;
    IDirect3DIndexBuffer9 *ib;
    IDirect3DTexture9 *tex;
    IDirect3DCubeTexture9 *cube;
    D3DLOCKED_RECT lr;
    D3DMATERIAL9 m;
    D3DLIGHT9 l;
    D3DMATRIX view, proj, ortho, world = mat_identity();
    ColorVertex ground[9 * 17], walls[12];
    WORD ground_idx[8 * 16 * 6], wall_idx[18];
    int frame, c, i, j, k, f;

    create_device("ff_fog_texgen", argc, argv);
    create_sphere(&vb, &ib);

    CHECK(IDirect3DDevice9_CreateTexture(g_dev, 16, 16, 1, 0, D3DFMT_A8R8G8B8, D3DPOOL_MANAGED, &tex, NULL));
    CHECK(IDirect3DTexture9_LockRect(tex, 0, &lr, NULL, 0));
    for (j = 0; j < 16; j++)
        for (i = 0; i < 16; i++)
            ((DWORD *)((BYTE *)lr.pBits + j * lr.Pitch))[i] = gradient(i, j, -1);
    CHECK(IDirect3DTexture9_UnlockRect(tex, 0));
    CHECK(IDirect3DDevice9_CreateCubeTexture(g_dev, 16, 1, 0, D3DFMT_A8R8G8B8, D3DPOOL_MANAGED, &cube, NULL));
    for (f = 0; f < 6; f++) {
        CHECK(IDirect3DCubeTexture9_LockRect(cube, (D3DCUBEMAP_FACES)f, 0, &lr, NULL, 0));
        for (j = 0; j < 16; j++)
            for (i = 0; i < 16; i++)
                ((DWORD *)((BYTE *)lr.pBits + j * lr.Pitch))[i] = gradient(i, j, f);
        CHECK(IDirect3DCubeTexture9_UnlockRect(cube, (D3DCUBEMAP_FACES)f, 0));
    }

    /* ground grid y = -1, x -4..4, z 0..16; three upright quads */
    for (j = 0, k = 0; j <= 16; j++)
        for (i = 0; i <= 8; i++, k++) {
            ground[k].x = -4.0f + i; ground[k].y = -1.0f; ground[k].z = (float)j;
            ground[k].color = ((i + j) & 1) ? 0xffe0d0a0 : 0xff80a060;
        }
    for (j = 0, k = 0; j < 16; j++)
        for (i = 0; i < 8; i++) {
            WORD a = j * 9 + i;
            ground_idx[k++] = a; ground_idx[k++] = a + 9; ground_idx[k++] = a + 1;
            ground_idx[k++] = a + 1; ground_idx[k++] = a + 9; ground_idx[k++] = a + 10;
        }
    for (i = 0; i < 3; i++) {
        static const float depth[3] = { 3, 7, 12 }, xs[3] = { -2.0f, 0.5f, 1.5f };
        static const DWORD colour[3] = { 0xffff3030, 0xff30ff30, 0xff3030ff };
        for (k = 0; k < 4; k++) {
            ColorVertex *v = &walls[i * 4 + k];
            v->x = xs[i] + ((k & 1) ? 1.6f : 0.0f);
            v->y = (k & 2) ? -1.0f : 1.2f;
            v->z = depth[i] + ((k & 1) ? 1.0f : 0.0f);   /* turned: range fog differs across it */
            v->color = colour[i];
        }
        wall_idx[i * 6 + 0] = i * 4; wall_idx[i * 6 + 1] = i * 4 + 1; wall_idx[i * 6 + 2] = i * 4 + 2;
        wall_idx[i * 6 + 3] = i * 4 + 1; wall_idx[i * 6 + 4] = i * 4 + 3; wall_idx[i * 6 + 5] = i * 4 + 2;
    }

    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_ZENABLE, D3DZB_TRUE));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_CULLMODE, D3DCULL_NONE));

    for (frame = 0; frame < 2; frame++) {
        clear_all(D3DCOLOR_XRGB(0x18, 0x18, 0x28));
        CHECK(IDirect3DDevice9_BeginScene(g_dev));
        if (frame == 0) {
            static const DWORD fogcolour[8] = { 0xff8090a0, 0xffa08060, 0xff6080a0, 0xffc0c0c0,
                                                0xff90a080, 0xffa0a0ff, 0xffffa0a0, 0xffa0ffa0 };
            view = mat_look_at_lh(v3(0, 0.8f, -1.5f), v3(0, 0, 6), v3(0, 1, 0));
            proj = mat_perspective_fov_lh(3.14159265f / 3, 2.0f, 0.5f, 20.0f);
            memset(&ortho, 0, sizeof ortho);    /* x -5..5, y -2.5..2.5, z 0..16 */
            ortho._11 = 0.2f; ortho._22 = 0.4f; ortho._33 = 1.0f / 16; ortho._44 = 1.0f;
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_WORLD, &world));
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_VIEW, &view));
            rs(D3DRS_LIGHTING, FALSE);
            rs(D3DRS_FOGENABLE, TRUE);
            CHECK(IDirect3DDevice9_SetFVF(g_dev, D3DFVF_XYZ | D3DFVF_DIFFUSE));
            for (c = 0; c < 8; c++) {
                D3DVIEWPORT9 vp = { (DWORD)((c & 1) * 128), (DWORD)((c >> 1) * 64), 128, 64, 0.0f, 1.0f };
                CHECK(IDirect3DDevice9_SetViewport(g_dev, &vp));
                rs(D3DRS_FOGCOLOR, fogcolour[c]);
                rs(D3DRS_FOGTABLEMODE, D3DFOG_NONE);
                rs(D3DRS_FOGVERTEXMODE, D3DFOG_NONE);
                rs(D3DRS_RANGEFOGENABLE, FALSE);
                rs(D3DRS_FOGSTART, f2dw(2.0f));
                rs(D3DRS_FOGEND, f2dw(14.0f));
                rs(D3DRS_FOGDENSITY, f2dw(0.15f));
                CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_PROJECTION, c >= 4 && c < 7 ? &ortho : &proj));
                switch (c) {
                case 0: rs(D3DRS_FOGVERTEXMODE, D3DFOG_LINEAR); break;
                case 1: rs(D3DRS_FOGVERTEXMODE, D3DFOG_EXP); break;
                case 2: rs(D3DRS_FOGVERTEXMODE, D3DFOG_EXP2); rs(D3DRS_FOGDENSITY, f2dw(0.12f)); break;
                case 3: rs(D3DRS_FOGVERTEXMODE, D3DFOG_LINEAR); rs(D3DRS_RANGEFOGENABLE, TRUE); break;
                case 4:
                    rs(D3DRS_FOGTABLEMODE, D3DFOG_LINEAR);
                    rs(D3DRS_FOGSTART, f2dw(0.2f));
                    rs(D3DRS_FOGEND, f2dw(0.9f));
                    break;
                case 5: rs(D3DRS_FOGTABLEMODE, D3DFOG_EXP); rs(D3DRS_FOGDENSITY, f2dw(2.0f)); break;
                case 6: rs(D3DRS_FOGTABLEMODE, D3DFOG_EXP2); rs(D3DRS_FOGDENSITY, f2dw(1.8f)); break;
                case 7: rs(D3DRS_FOGTABLEMODE, D3DFOG_LINEAR); break;
                }
                CHECK(IDirect3DDevice9_DrawIndexedPrimitiveUP(g_dev, D3DPT_TRIANGLELIST, 0, 9 * 17, 8 * 16 * 2,
                                                              ground_idx, D3DFMT_INDEX16, ground, sizeof(ColorVertex)));
                CHECK(IDirect3DDevice9_DrawIndexedPrimitiveUP(g_dev, D3DPT_TRIANGLELIST, 0, 12, 6, wall_idx,
                                                              D3DFMT_INDEX16, walls, sizeof(ColorVertex)));
            }
            rs(D3DRS_FOGENABLE, FALSE);
        } else {
            D3DMATRIX t;
            view = mat_look_at_lh(v3(0, 0.8f, -4.5f), v3(0, 0, 0), v3(0, 1, 0));
            proj = mat_perspective_fov_lh(3.14159265f / 4, 85.0f / 128.0f, 1.0f, 10.0f);
            world = mat_rotation_y(0.4f);
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_WORLD, &world));
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_VIEW, &view));
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_PROJECTION, &proj));
            /* lit, modulated by the texture */
            memset(&m, 0, sizeof m);
            m.Diffuse = rgba(1, 1, 1, 1);
            m.Ambient = rgba(1, 1, 1, 1);
            CHECK(IDirect3DDevice9_SetMaterial(g_dev, &m));
            memset(&l, 0, sizeof l);
            l.Type = D3DLIGHT_DIRECTIONAL;
            l.Diffuse = rgba(0.7f, 0.7f, 0.7f, 1);
            l.Direction.x = -0.3f; l.Direction.y = -0.4f; l.Direction.z = 0.8f;
            CHECK(IDirect3DDevice9_SetLight(g_dev, 0, &l));
            CHECK(IDirect3DDevice9_LightEnable(g_dev, 0, TRUE));
            rs(D3DRS_LIGHTING, TRUE);
            rs(D3DRS_AMBIENT, 0xff505050);
            CHECK(IDirect3DDevice9_SetFVF(g_dev, FVF_SPHERE));
            CHECK(IDirect3DDevice9_SetStreamSource(g_dev, 0, vb, 0, sizeof(SphereVertex)));
            CHECK(IDirect3DDevice9_SetIndices(g_dev, ib));
            for (i = 0; i < 2; i++) {
                CHECK(IDirect3DDevice9_SetSamplerState(g_dev, 0, D3DSAMP_MINFILTER, D3DTEXF_LINEAR));
                CHECK(IDirect3DDevice9_SetSamplerState(g_dev, 0, D3DSAMP_MAGFILTER, D3DTEXF_LINEAR));
                CHECK(IDirect3DDevice9_SetSamplerState(g_dev, 0, D3DSAMP_ADDRESSU, D3DTADDRESS_CLAMP));
                CHECK(IDirect3DDevice9_SetSamplerState(g_dev, 0, D3DSAMP_ADDRESSV, D3DTADDRESS_CLAMP));
            }
            ts(0, D3DTSS_COLOROP, D3DTOP_MODULATE);
            ts(0, D3DTSS_COLORARG1, D3DTA_TEXTURE);
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            for (c = 0; c < 6; c++) {
                D3DVIEWPORT9 vp = { (DWORD)((c % 3) * 85), (DWORD)((c / 3) * 128), 85, 128, 0.0f, 1.0f };
                CHECK(IDirect3DDevice9_SetViewport(g_dev, &vp));
                rs(D3DRS_LOCALVIEWER, TRUE);
                CHECK(IDirect3DDevice9_SetTexture(g_dev, 0, (IDirect3DBaseTexture9 *)tex));
                t = mat_identity();
                switch (c) {
                case 0:          /* normal (-1..1) -> (0..1) */
                case 1:          /* camera-space position, x/y of a radius-1 sphere at z = 3 */
                    t._11 = 0.5f; t._22 = -0.5f; t._41 = 0.5f; t._42 = 0.5f;
                    if (c == 1) { t._42 = 0.5f + 0.5f * 0.17f; t._33 = 0.5f; }
                    ts(0, D3DTSS_TEXCOORDINDEX, c == 0 ? D3DTSS_TCI_CAMERASPACENORMAL : D3DTSS_TCI_CAMERASPACEPOSITION);
                    ts(0, D3DTSS_TEXTURETRANSFORMFLAGS, D3DTTFF_COUNT2);
                    break;
                case 2:
                case 3:
                    rs(D3DRS_LOCALVIEWER, c == 2);
                    CHECK(IDirect3DDevice9_SetTexture(g_dev, 0, (IDirect3DBaseTexture9 *)cube));
                    t = mat_rotation_y(0.3f);
                    ts(0, D3DTSS_TEXCOORDINDEX, D3DTSS_TCI_CAMERASPACEREFLECTIONVECTOR);
                    ts(0, D3DTSS_TEXTURETRANSFORMFLAGS, D3DTTFF_COUNT3);
                    break;
                case 4:
                    ts(0, D3DTSS_TEXCOORDINDEX, D3DTSS_TCI_SPHEREMAP);
                    ts(0, D3DTSS_TEXTURETRANSFORMFLAGS, D3DTTFF_DISABLE);
                    break;
                case 5:          /* (u, v, 1) -> (2u, v + 0.5 (u - 0.5), 1 + u) / (1 + u) */
                    /* rows 3 and 4 equal: D3D9 extends a 2D set to (u, v, 1, 0), Wine (under
                       PROJECTED only) to (u, v, 0, 1); both give the same coordinate here */
                    t._11 = 2.0f; t._12 = 0.5f; t._13 = 1.0f;
                    t._32 = -0.25f; t._33 = 1.0f;
                    t._41 = 0.0f; t._42 = -0.25f; t._43 = 1.0f; t._44 = 0.0f;
                    ts(0, D3DTSS_TEXCOORDINDEX, 0);
                    ts(0, D3DTSS_TEXTURETRANSFORMFLAGS, D3DTTFF_COUNT3 | D3DTTFF_PROJECTED);
                    break;
                }
                CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_TEXTURE0, &t));
                draw_sphere();
            }
            ts(0, D3DTSS_TEXTURETRANSFORMFLAGS, D3DTTFF_DISABLE);
            ts(0, D3DTSS_TEXCOORDINDEX, 0);
            CHECK(IDirect3DDevice9_SetTexture(g_dev, 0, NULL));
        }
        CHECK(IDirect3DDevice9_EndScene(g_dev));
        save_frame(frame);
        CHECK(IDirect3DDevice9_Present(g_dev, NULL, NULL, NULL, NULL));
    }
    IDirect3DTexture9_Release(tex);
    IDirect3DCubeTexture9_Release(cube);
    IDirect3DVertexBuffer9_Release(vb);
    IDirect3DIndexBuffer9_Release(ib);
    destroy_device();
    return 0;
}
