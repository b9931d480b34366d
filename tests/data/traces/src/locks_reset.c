/*
 * locks_reset.c - the importer's partial and depth uploads and Reset, captured under Wine:
 *   frame 0: a 4x4x4 A8R8G8B8 volume texture, filled whole (every texel dark grey) and then
 *            through LockBox with a box {1,1,1, 3,3,2} (red); slice 1 drawn over a 4x4 block
 *            of the 256x256 back buffer with POINT sampling, one texel per pixel.
 *   D16_LOCKABLE and D32F_LOCKABLE 4x4 depth surfaces written whole and through a rectangle,
 *            then read back READONLY (the values printed to depth.txt).
 *   Reset to a 128x96 back buffer; frame 1: cleared green with a blue 8x8 rectangle.
 */
#include "common.h"

struct vtx { float x, y, z, rhw, u, v, w; };

static void volume_frame(void)
{
    IDirect3DVolumeTexture9 *vol;
    D3DLOCKED_BOX lb;
    D3DBOX box = { 1, 1, 3, 3, 1, 2 };  /* Left Top Right Bottom Front Back */
    unsigned x, y, z;
    struct vtx q[4];
    float w = 1.5f / 4.0f;

    CHECK(IDirect3DDevice9_CreateVolumeTexture(g_dev, 4, 4, 4, 1, 0, D3DFMT_A8R8G8B8, D3DPOOL_MANAGED, &vol, NULL));
    CHECK(IDirect3DVolumeTexture9_LockBox(vol, 0, &lb, NULL, 0));
    for (z = 0; z < 4; z++)
        for (y = 0; y < 4; y++)
            for (x = 0; x < 4; x++)
                ((DWORD *)((BYTE *)lb.pBits + z * lb.SlicePitch + y * lb.RowPitch))[x] = 0xFF404040u;
    CHECK(IDirect3DVolumeTexture9_UnlockBox(vol, 0));
    CHECK(IDirect3DVolumeTexture9_LockBox(vol, 0, &lb, &box, 0));
    for (z = 0; z < 1; z++)
        for (y = 0; y < 2; y++)
            for (x = 0; x < 2; x++)
                ((DWORD *)((BYTE *)lb.pBits + z * lb.SlicePitch + y * lb.RowPitch))[x] = 0xFFFF0000u + x * 0x80 + y * 0x8000;
    CHECK(IDirect3DVolumeTexture9_UnlockBox(vol, 0));

    /* pixels 8..11 x 8..11, texel (i, j) of slice 1 at pixel (8 + i, 8 + j) */
    q[0] = (struct vtx){ 8.0f - 0.5f, 8.0f - 0.5f, 0.5f, 1.0f, 0.0f, 0.0f, w };
    q[1] = (struct vtx){ 12.0f - 0.5f, 8.0f - 0.5f, 0.5f, 1.0f, 1.0f, 0.0f, w };
    q[2] = (struct vtx){ 8.0f - 0.5f, 12.0f - 0.5f, 0.5f, 1.0f, 0.0f, 1.0f, w };
    q[3] = (struct vtx){ 12.0f - 0.5f, 12.0f - 0.5f, 0.5f, 1.0f, 1.0f, 1.0f, w };
    CHECK(IDirect3DDevice9_Clear(g_dev, 0, NULL, D3DCLEAR_TARGET | D3DCLEAR_ZBUFFER, 0xFF000000u, 1.0f, 0));
    CHECK(IDirect3DDevice9_BeginScene(g_dev));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_LIGHTING, FALSE));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_ZENABLE, FALSE));
    CHECK(IDirect3DDevice9_SetTexture(g_dev, 0, (IDirect3DBaseTexture9 *)vol));
    CHECK(IDirect3DDevice9_SetSamplerState(g_dev, 0, D3DSAMP_MINFILTER, D3DTEXF_POINT));
    CHECK(IDirect3DDevice9_SetSamplerState(g_dev, 0, D3DSAMP_MAGFILTER, D3DTEXF_POINT));
    CHECK(IDirect3DDevice9_SetTextureStageState(g_dev, 0, D3DTSS_COLOROP, D3DTOP_SELECTARG1));
    CHECK(IDirect3DDevice9_SetTextureStageState(g_dev, 0, D3DTSS_COLORARG1, D3DTA_TEXTURE));
    CHECK(IDirect3DDevice9_SetFVF(g_dev, D3DFVF_XYZRHW | D3DFVF_TEX1 | D3DFVF_TEXCOORDSIZE3(0)));
    CHECK(IDirect3DDevice9_DrawPrimitiveUP(g_dev, D3DPT_TRIANGLESTRIP, 2, q, sizeof q[0]));
    CHECK(IDirect3DDevice9_EndScene(g_dev));
    save_frame(0);
    CHECK(IDirect3DDevice9_Present(g_dev, NULL, NULL, NULL, NULL));
    CHECK(IDirect3DDevice9_SetTexture(g_dev, 0, NULL));
    IDirect3DVolumeTexture9_Release(vol);
}

static void depth_surfaces(FILE *out)
{
    static const D3DFORMAT formats[2] = { D3DFMT_D16_LOCKABLE, D3DFMT_D32F_LOCKABLE };
    RECT rect = { 1, 2, 3, 4 };
    int i;
    unsigned x, y;

    for (i = 0; i < 2; i++) {
        IDirect3DSurface9 *ds;
        D3DLOCKED_RECT lr;
        CHECK(IDirect3DDevice9_CreateDepthStencilSurface(g_dev, 4, 4, formats[i], D3DMULTISAMPLE_NONE, 0, FALSE, &ds, NULL));
        {
            HRESULT hr = IDirect3DSurface9_LockRect(ds, &lr, NULL, 0);
            if (FAILED(hr)) {
                /* Wine refuses to map a depth surface it created without CPU access */
                fprintf(out, "format %d: LockRect failed, hr=0x%08lx\n", (int)formats[i], (unsigned long)hr);
                IDirect3DSurface9_Release(ds);
                continue;
            }
        }
        for (y = 0; y < 4; y++)
            for (x = 0; x < 4; x++) {
                BYTE *row = (BYTE *)lr.pBits + y * lr.Pitch;
                if (i == 0) ((WORD *)row)[x] = (WORD)(0x1000 * y + 0x100 * x);
                else ((float *)row)[x] = 0.0625f * (float)(4 * y + x);
            }
        CHECK(IDirect3DSurface9_UnlockRect(ds));
        CHECK(IDirect3DSurface9_LockRect(ds, &lr, &rect, 0));
        for (y = 0; y < 2; y++)
            for (x = 0; x < 2; x++) {
                BYTE *row = (BYTE *)lr.pBits + y * lr.Pitch;
                if (i == 0) ((WORD *)row)[x] = (WORD)(0xF000 + x + 2 * y);
                else ((float *)row)[x] = 0.75f + 0.125f * (float)(x + 2 * y) / 4.0f;
            }
        CHECK(IDirect3DSurface9_UnlockRect(ds));
        CHECK(IDirect3DSurface9_LockRect(ds, &lr, NULL, D3DLOCK_READONLY));
        for (y = 0; y < 4; y++) {
            for (x = 0; x < 4; x++) {
                const BYTE *row = (const BYTE *)lr.pBits + y * lr.Pitch;
                if (i == 0) fprintf(out, " %u", ((const WORD *)row)[x]);
                else fprintf(out, " %.9g", ((const float *)row)[x]);
            }
            fprintf(out, "\n");
        }
        CHECK(IDirect3DSurface9_UnlockRect(ds));
        IDirect3DSurface9_Release(ds);
    }
}

static void reset_frame(void)
{
    D3DPRESENT_PARAMETERS pp;
    D3DRECT r = { 4, 4, 12, 12 };

    memset(&pp, 0, sizeof pp);
    pp.BackBufferWidth = 128;
    pp.BackBufferHeight = 96;
    pp.BackBufferFormat = D3DFMT_X8R8G8B8;
    pp.BackBufferCount = 1;
    pp.SwapEffect = D3DSWAPEFFECT_DISCARD;
    pp.hDeviceWindow = g_wnd;
    pp.Windowed = TRUE;
    pp.EnableAutoDepthStencil = TRUE;
    pp.AutoDepthStencilFormat = D3DFMT_D24S8;
    pp.PresentationInterval = D3DPRESENT_INTERVAL_IMMEDIATE;
    CHECK(IDirect3DDevice9_Reset(g_dev, &pp));
    CHECK(IDirect3DDevice9_Clear(g_dev, 0, NULL, D3DCLEAR_TARGET, 0xFF00FF00u, 1.0f, 0));
    CHECK(IDirect3DDevice9_Clear(g_dev, 1, &r, D3DCLEAR_TARGET, 0xFF0000FFu, 1.0f, 0));
    save_frame(1);
    CHECK(IDirect3DDevice9_Present(g_dev, NULL, NULL, NULL, NULL));
}

int main(int argc, char **argv)
{
    char path[MAX_PATH];
    FILE *out;

    create_device("locks_reset", argc, argv);
    volume_frame();
    snprintf(path, sizeof path, "%s\\depth.txt", g_outdir);
    out = fopen(path, "w");
    if (!out) return 1;
    depth_surfaces(out);
    fclose(out);
    reset_frame();
    destroy_device();
    return 0;
}
