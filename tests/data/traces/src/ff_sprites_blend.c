/*
 * ff_sprites_blend.c - fixed-function point sprites and vertex blending (no shaders).
 *
 * frame 0, points (DrawPrimitiveUP point lists, z-buffered, alpha-tested sprite texture):
 *   top half: a 6x3 field of points receding in depth (XYZ|DIFFUSE) with POINTSPRITEENABLE and
 *   POINTSCALEENABLE (POINTSIZE 0.5, A 0, B 0, C 1 / A 1, B 0.2, C 0: size Vh sqrt(1/(A+B De+C De^2))),
 *   POINTSIZE_MIN 3 and POINTSIZE_MAX 40, textured by an 8x8 disc (POINT filtered);
 *   bottom-left: XYZ|PSIZE|DIFFUSE points with their own sizes, sprites without scaling;
 *   bottom-right: points without POINTSPRITEENABLE (flat squares of POINTSIZE 9, untextured).
 * frame 1, vertex blending of a lit ribbon (8 x 2 quads along x, bent by the blend):
 *   row 0: VERTEXBLEND 1WEIGHTS (XYZB1|NORMAL|DIFFUSE), WORLD identity, WORLD1 a rotation about z,
 *          weight = x position;
 *   row 1: 2WEIGHTS (XYZB2|NORMAL|DIFFUSE), WORLD, WORLD1, WORLD2;
 *   row 2: INDEXEDVERTEXBLENDENABLE with 1WEIGHTS (XYZB2|LASTBETA_UBYTE4|NORMAL|DIFFUSE), the
 *          indices choosing WORLDMATRIX(0..5) per segment;
 *   row 3: 0WEIGHTS with INDEXEDVERTEXBLENDENABLE (one index per vertex, weight 1).
 */
#include "common.h"

typedef struct { float x, y, z; DWORD color; } PointVertex;
typedef struct { float x, y, z, size; DWORD color; } SizedPoint;
typedef struct { float x, y, z, w0, nx, ny, nz; DWORD color; } B1Vertex;
typedef struct { float x, y, z, w0, w1, nx, ny, nz; DWORD color; } B2Vertex;
typedef struct { float x, y, z, w0; DWORD indices; float nx, ny, nz; DWORD color; } IdxVertex;

static void rs(D3DRENDERSTATETYPE s, DWORD v) { CHECK(IDirect3DDevice9_SetRenderState(g_dev, s, v)); }

static void viewport(DWORD x, DWORD y, DWORD w, DWORD h)
{
    D3DVIEWPORT9 vp = { x, y, w, h, 0.0f, 1.0f };
    CHECK(IDirect3DDevice9_SetViewport(g_dev, &vp));
}

int main(int argc, char **argv)
{
    IDirect3DTexture9 *tex;
    D3DLOCKED_RECT lr;
    D3DMATRIX view, proj, world;
    D3DMATERIAL9 m;
    D3DLIGHT9 l;
    PointVertex field[18], flat[12];
    SizedPoint sized[8];
    B1Vertex b1[18];
    B2Vertex b2[18];
    IdxVertex ix[18];
    WORD idx[8 * 6];
    int frame, i, j, k;

    create_device("ff_sprites_blend", argc, argv);
    CHECK(IDirect3DDevice9_CreateTexture(g_dev, 8, 8, 1, 0, D3DFMT_A8R8G8B8, D3DPOOL_MANAGED, &tex, NULL));
    CHECK(IDirect3DTexture9_LockRect(tex, 0, &lr, NULL, 0));
    for (j = 0; j < 8; j++)
        for (i = 0; i < 8; i++) {
            int dx = 2 * i - 7, dy = 2 * j - 7;
            DWORD a = dx * dx + dy * dy <= 50 ? 0xff : 0x00;
            DWORD c = (i < 4 ? 0xffffff : 0xc0c0ff) & (j < 4 ? 0xffffff : 0xffc0c0);
            ((DWORD *)((BYTE *)lr.pBits + j * lr.Pitch))[i] = (a << 24) | c;
        }
    CHECK(IDirect3DTexture9_UnlockRect(tex, 0));
    CHECK(IDirect3DDevice9_SetSamplerState(g_dev, 0, D3DSAMP_MINFILTER, D3DTEXF_POINT));
    CHECK(IDirect3DDevice9_SetSamplerState(g_dev, 0, D3DSAMP_MAGFILTER, D3DTEXF_POINT));

    for (j = 0, k = 0; j < 3; j++)
        for (i = 0; i < 6; i++, k++) {
            field[k].z = 1.0f + 1.5f * i + 0.5f * j;      /* every centre inside the view */
            field[k].x = (-0.5f + 0.2f * i) * field[k].z; field[k].y = (-0.23f + 0.25f * j) * field[k].z;
            field[k].color = D3DCOLOR_XRGB(255 - 40 * i, 80 + 80 * j, 60 + 30 * i);
        }
    for (i = 0; i < 8; i++) {
        sized[i].x = -0.85f + 0.24f * i; sized[i].y = (i & 1) ? 0.3f : -0.3f; sized[i].z = 0.5f;
        sized[i].size = 4.0f + 5.0f * i;
        sized[i].color = D3DCOLOR_XRGB(255, 255 - 30 * i, 40 * i);
    }
    for (i = 0; i < 12; i++) {
        flat[i].x = -0.8f + 0.32f * (i % 6); flat[i].y = (i < 6) ? 0.4f : -0.4f; flat[i].z = 0.5f;
        flat[i].color = D3DCOLOR_XRGB(60 + 16 * i, 200, 255 - 16 * i);
    }

    /* ribbon: 9 columns x 2 rows of vertices, x -2..2, y -0.3..0.3 */
    for (i = 0, k = 0; i <= 8; i++)
        for (j = 0; j < 2; j++, k++) {
            float x = -2.0f + 0.5f * i, y = j ? 0.3f : -0.3f, t = i / 8.0f;
            DWORD col = D3DCOLOR_XRGB(255, 120 + 15 * i, 80 + 100 * j);
            b1[k] = (B1Vertex){ x, y, 0, t, 0, 0, -1, col };
            b2[k] = (B2Vertex){ x, y, 0, (1 - t) * (1 - t), 2 * t * (1 - t), 0, 0, -1, col };
            /* segment i blends WORLDMATRIX(i/2) and WORLDMATRIX(i/2 + 1) */
            ix[k] = (IdxVertex){ x, y, 0, 1.0f - 0.5f * (i & 1), (DWORD)((i / 2) | ((i / 2 + 1) << 8)), 0, 0, -1, col };
        }
    for (i = 0, k = 0; i < 8; i++) {
        WORD a = i * 2;
        idx[k++] = a; idx[k++] = a + 1; idx[k++] = a + 2;
        idx[k++] = a + 2; idx[k++] = a + 1; idx[k++] = a + 3;
    }

    view = mat_look_at_lh(v3(0, 0, -4), v3(0, 0, 0), v3(0, 1, 0));
    CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_VIEW, &view));
    rs(D3DRS_ZENABLE, D3DZB_TRUE);
    rs(D3DRS_CULLMODE, D3DCULL_NONE);
    rs(D3DRS_LIGHTING, FALSE);

    for (frame = 0; frame < 2; frame++) {
        viewport(0, 0, WIDTH, HEIGHT);
        CHECK(IDirect3DDevice9_Clear(g_dev, 0, NULL, D3DCLEAR_TARGET | D3DCLEAR_ZBUFFER,
                                     D3DCOLOR_XRGB(0x20, 0x28, 0x30), 1.0f, 0));
        CHECK(IDirect3DDevice9_BeginScene(g_dev));
        if (frame == 0) {
            world = mat_identity();
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_WORLD, &world));
            view = mat_identity();
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_VIEW, &view));
            proj = mat_perspective_fov_lh(3.14159265f / 3, 2.0f, 0.25f, 20.0f);
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_PROJECTION, &proj));
            CHECK(IDirect3DDevice9_SetTexture(g_dev, 0, (IDirect3DBaseTexture9 *)tex));
            CHECK(IDirect3DDevice9_SetTextureStageState(g_dev, 0, D3DTSS_COLOROP, D3DTOP_MODULATE));
            CHECK(IDirect3DDevice9_SetTextureStageState(g_dev, 0, D3DTSS_COLORARG2, D3DTA_DIFFUSE));
            rs(D3DRS_ALPHATESTENABLE, TRUE);
            rs(D3DRS_ALPHAREF, 0x80);
            rs(D3DRS_ALPHAFUNC, D3DCMP_GREATEREQUAL);
            rs(D3DRS_POINTSPRITEENABLE, TRUE);
            rs(D3DRS_POINTSCALEENABLE, TRUE);
            rs(D3DRS_POINTSIZE_MIN, f2dw(3.0f));
            rs(D3DRS_POINTSIZE_MAX, f2dw(40.0f));
            CHECK(IDirect3DDevice9_SetFVF(g_dev, D3DFVF_XYZ | D3DFVF_DIFFUSE));
            /* left half: A 0 B 0 C 1; right half: A 1 B 0.2 C 0 */
            for (i = 0; i < 2; i++) {
                viewport(i * 128, 0, 128, 128);
                rs(D3DRS_POINTSIZE, f2dw(i ? 12.0f : 0.5f));
                rs(D3DRS_POINTSCALE_A, f2dw(i ? 1.0f : 0.0f));
                rs(D3DRS_POINTSCALE_B, f2dw(i ? 0.2f : 0.0f));
                rs(D3DRS_POINTSCALE_C, f2dw(i ? 0.0f : 1.0f));
                CHECK(IDirect3DDevice9_DrawPrimitiveUP(g_dev, D3DPT_POINTLIST, 18, field, sizeof(PointVertex)));
            }
            /* bottom left: per-vertex sizes, no scaling (screen pixels) */
            proj = mat_identity();
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_PROJECTION, &proj));
            viewport(0, 128, 128, 128);
            rs(D3DRS_POINTSCALEENABLE, FALSE);
            rs(D3DRS_POINTSIZE_MIN, f2dw(1.0f));
            rs(D3DRS_POINTSIZE_MAX, f2dw(64.0f));
            CHECK(IDirect3DDevice9_SetFVF(g_dev, D3DFVF_XYZ | D3DFVF_PSIZE | D3DFVF_DIFFUSE));
            CHECK(IDirect3DDevice9_DrawPrimitiveUP(g_dev, D3DPT_POINTLIST, 8, sized, sizeof(SizedPoint)));
            /* bottom right: no sprites, untextured squares */
            viewport(128, 128, 128, 128);
            rs(D3DRS_POINTSPRITEENABLE, FALSE);
            rs(D3DRS_ALPHATESTENABLE, FALSE);
            rs(D3DRS_POINTSIZE, f2dw(9.0f));
            CHECK(IDirect3DDevice9_SetTexture(g_dev, 0, NULL));
            CHECK(IDirect3DDevice9_SetFVF(g_dev, D3DFVF_XYZ | D3DFVF_DIFFUSE));
            CHECK(IDirect3DDevice9_DrawPrimitiveUP(g_dev, D3DPT_POINTLIST, 12, flat, sizeof(PointVertex)));
        } else {
            D3DMATRIX w;
            view = mat_look_at_lh(v3(0, 0, -4), v3(0, 0, 0), v3(0, 1, 0));
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_VIEW, &view));
            proj = mat_perspective_fov_lh(3.14159265f / 8, 4.0f, 1.0f, 10.0f);
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_PROJECTION, &proj));
            CHECK(IDirect3DDevice9_SetTextureStageState(g_dev, 0, D3DTSS_COLOROP, D3DTOP_SELECTARG2));
            memset(&m, 0, sizeof m);
            m.Ambient = m.Diffuse = (D3DCOLORVALUE){ 1, 1, 1, 1 };
            CHECK(IDirect3DDevice9_SetMaterial(g_dev, &m));
            memset(&l, 0, sizeof l);
            l.Type = D3DLIGHT_DIRECTIONAL;
            l.Diffuse = (D3DCOLORVALUE){ 0.8f, 0.8f, 0.8f, 1 };
            l.Direction.x = 0.4f; l.Direction.y = -0.2f; l.Direction.z = 1.0f;
            CHECK(IDirect3DDevice9_SetLight(g_dev, 0, &l));
            CHECK(IDirect3DDevice9_LightEnable(g_dev, 0, TRUE));
            rs(D3DRS_LIGHTING, TRUE);
            rs(D3DRS_AMBIENT, 0xff303030);
            rs(D3DRS_COLORVERTEX, TRUE);
            rs(D3DRS_NORMALIZENORMALS, TRUE);

            /* row 0: 1 weight, WORLD identity, WORLD1 turned about z and y */
            viewport(0, 0, 256, 64);
            w = mat_identity();
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_WORLD, &w));
            w = mat_rotation_z(0.5f);
            { D3DMATRIX ry = mat_rotation_y(0.8f); w = mat_mul(&w, &ry); }
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_WORLD1, &w));
            rs(D3DRS_VERTEXBLEND, D3DVBF_1WEIGHTS);
            CHECK(IDirect3DDevice9_SetFVF(g_dev, D3DFVF_XYZB1 | D3DFVF_NORMAL | D3DFVF_DIFFUSE));
            CHECK(IDirect3DDevice9_DrawIndexedPrimitiveUP(g_dev, D3DPT_TRIANGLELIST, 0, 18, 16, idx, D3DFMT_INDEX16,
                                                          b1, sizeof(B1Vertex)));
            /* row 1: 2 weights, three matrices */
            viewport(0, 64, 256, 64);
            w = mat_translation(0, -0.5f, 0);
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_WORLD, &w));
            w = mat_translation(0, 1.0f, 0.5f);
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_WORLD1, &w));
            w = mat_rotation_x(-0.9f);
            CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_WORLD2, &w));
            rs(D3DRS_VERTEXBLEND, D3DVBF_2WEIGHTS);
            CHECK(IDirect3DDevice9_SetFVF(g_dev, D3DFVF_XYZB2 | D3DFVF_NORMAL | D3DFVF_DIFFUSE));
            CHECK(IDirect3DDevice9_DrawIndexedPrimitiveUP(g_dev, D3DPT_TRIANGLELIST, 0, 18, 16, idx, D3DFMT_INDEX16,
                                                          b2, sizeof(B2Vertex)));
            /* rows 2 and 3: indexed, WORLDMATRIX(0..5) a fan of rotations about y and x */
            for (i = 0; i < 6; i++) {
                D3DMATRIX r1 = mat_rotation_y(0.35f * (i - 2.5f)), r2 = mat_rotation_x(0.3f * (i & 1 ? 1 : -1));
                w = mat_mul(&r1, &r2);
                CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_WORLDMATRIX(i), &w));
            }
            rs(D3DRS_INDEXEDVERTEXBLENDENABLE, TRUE);
            CHECK(IDirect3DDevice9_SetFVF(g_dev, D3DFVF_XYZB2 | D3DFVF_LASTBETA_UBYTE4 | D3DFVF_NORMAL | D3DFVF_DIFFUSE));
            viewport(0, 128, 256, 64);
            rs(D3DRS_VERTEXBLEND, D3DVBF_1WEIGHTS);
            CHECK(IDirect3DDevice9_DrawIndexedPrimitiveUP(g_dev, D3DPT_TRIANGLELIST, 0, 18, 16, idx, D3DFMT_INDEX16,
                                                          ix, sizeof(IdxVertex)));
            viewport(0, 192, 256, 64);
            rs(D3DRS_VERTEXBLEND, D3DVBF_0WEIGHTS);
            CHECK(IDirect3DDevice9_DrawIndexedPrimitiveUP(g_dev, D3DPT_TRIANGLELIST, 0, 18, 16, idx, D3DFMT_INDEX16,
                                                          ix, sizeof(IdxVertex)));
            rs(D3DRS_INDEXEDVERTEXBLENDENABLE, FALSE);
            rs(D3DRS_VERTEXBLEND, D3DVBF_DISABLE);
        }
        CHECK(IDirect3DDevice9_EndScene(g_dev));
        save_frame(frame);
        CHECK(IDirect3DDevice9_Present(g_dev, NULL, NULL, NULL, NULL));
    }
    IDirect3DTexture9_Release(tex);
    destroy_device();
    return 0;
}
