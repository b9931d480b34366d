/*
 * ff_texops.c - fixed-function texture stage operations (no shaders).
 *
 * Pre-transformed (XYZRHW|DIFFUSE|SPECULAR|TEX2) quads drawn with DrawPrimitiveUP in a 6x6 grid of
 * 40x40 cells, each cell one texture-stage setup.  Two 8x8 A8R8G8B8 textures filled with LockRect,
 * POINT filtered and mapped one texel per 5x5 pixels (no filtering, no ties); each quad has one
 * diffuse and one specular colour at all four corners, so every input is an exact 8-bit value.
 *  frame 0: stage 0 colour ops on TEXTURE (arg1) and DIFFUSE (arg2), every D3DTOP but PREMODULATE
 *           and the bump ops, then alpha ops made visible by a stage 1 that selects
 *           CURRENT|ALPHAREPLICATE, then argument modifiers (COMPLEMENT, ALPHAREPLICATE, TFACTOR,
 *           SPECULAR).
 *  frame 1: two and three stages with the second texture: TEMP results, TFACTOR, CONSTANT, LERP,
 *           MULTIPLYADD, DOTPRODUCT3, BLENDCURRENTALPHA, ALPHAOP DISABLE keeping the alpha,
 *           SPECULARENABLE, TEXCOORDINDEX.
 */
#include "common.h"

typedef struct { float x, y, z, rhw; DWORD diffuse, specular; float u0, v0, u1, v1; } Vertex;
#define FVF (D3DFVF_XYZRHW | D3DFVF_DIFFUSE | D3DFVF_SPECULAR | D3DFVF_TEX2)

static IDirect3DTexture9 *g_tex[2];

static void fill(IDirect3DTexture9 *tex, int which)
{
    D3DLOCKED_RECT lr;
    int x, y;
    CHECK(IDirect3DTexture9_LockRect(tex, 0, &lr, NULL, 0));
    for (y = 0; y < 8; y++) {
        DWORD *row = (DWORD *)((BYTE *)lr.pBits + y * lr.Pitch);
        for (x = 0; x < 8; x++) {
            DWORD a, r, g, b;
            if (which == 0) {
                r = x * 32 + 16; g = y * 32 + 16; b = ((x ^ y) & 1) ? 0xe0 : 0x30; a = (x + y) * 17;
            } else {
                r = 255 - x * 32; g = ((x + y) & 2) ? 0xc8 : 0x38; b = y * 36; a = 255 - y * 30;
            }
            row[x] = (a << 24) | (r << 16) | (g << 8) | b;
        }
    }
    CHECK(IDirect3DTexture9_UnlockRect(tex, 0));
}

static void ts(DWORD stage, D3DTEXTURESTAGESTATETYPE t, DWORD v)
{
    CHECK(IDirect3DDevice9_SetTextureStageState(g_dev, stage, t, v));
}

/* back to the defaults used by every cell */
static void reset_stages(void)
{
    DWORD s;
    for (s = 0; s < 3; s++) {
        ts(s, D3DTSS_COLOROP, s == 0 ? D3DTOP_MODULATE : D3DTOP_DISABLE);
        ts(s, D3DTSS_ALPHAOP, s == 0 ? D3DTOP_SELECTARG1 : D3DTOP_DISABLE);
        ts(s, D3DTSS_COLORARG1, D3DTA_TEXTURE);
        ts(s, D3DTSS_COLORARG2, D3DTA_CURRENT);
        ts(s, D3DTSS_COLORARG0, D3DTA_CURRENT);
        ts(s, D3DTSS_ALPHAARG1, D3DTA_TEXTURE);
        ts(s, D3DTSS_ALPHAARG2, D3DTA_CURRENT);
        ts(s, D3DTSS_ALPHAARG0, D3DTA_CURRENT);
        ts(s, D3DTSS_RESULTARG, D3DTA_CURRENT);
        ts(s, D3DTSS_TEXCOORDINDEX, s < 2 ? s : 0);
    }
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_SPECULARENABLE, FALSE));
}

/* one 40x40 cell (pixel centres at integers: edges on .5) */
static void cell(int index, DWORD diffuse, DWORD specular)
{
    float x0 = 2.0f + (index % 6) * 42 - 0.5f, y0 = 2.0f + (index / 6) * 42 - 0.5f;
    Vertex v[4] = {
        { x0, y0, 0.5f, 1.0f, diffuse, specular, 0, 0, 1, 0 },
        { x0 + 40, y0, 0.5f, 1.0f, diffuse, specular, 1, 0, 1, 1 },
        { x0, y0 + 40, 0.5f, 1.0f, diffuse, specular, 0, 1, 0, 0 },
        { x0 + 40, y0 + 40, 0.5f, 1.0f, diffuse, specular, 1, 1, 0, 1 },
    };
    CHECK(IDirect3DDevice9_DrawPrimitiveUP(g_dev, D3DPT_TRIANGLESTRIP, 2, v, sizeof(Vertex)));
}

static const DWORD kDiffuse[4] = { 0x80c06030, 0x4020a0e0, 0xe0ff8000, 0x20408040 };

int main(int argc, char **argv)
{
    static const D3DTEXTUREOP colour_ops[] = {
        D3DTOP_SELECTARG1, D3DTOP_SELECTARG2, D3DTOP_MODULATE, D3DTOP_MODULATE2X, D3DTOP_MODULATE4X,
        D3DTOP_ADD, D3DTOP_ADDSIGNED, D3DTOP_ADDSIGNED2X, D3DTOP_SUBTRACT, D3DTOP_ADDSMOOTH,
        D3DTOP_BLENDDIFFUSEALPHA, D3DTOP_BLENDTEXTUREALPHA, D3DTOP_BLENDFACTORALPHA,
        D3DTOP_BLENDTEXTUREALPHAPM, D3DTOP_BLENDCURRENTALPHA, D3DTOP_MODULATEALPHA_ADDCOLOR,
        D3DTOP_MODULATECOLOR_ADDALPHA, D3DTOP_MODULATEINVALPHA_ADDCOLOR,
        D3DTOP_MODULATEINVCOLOR_ADDALPHA, D3DTOP_DOTPRODUCT3, D3DTOP_MULTIPLYADD, D3DTOP_LERP,
    };
    static const D3DTEXTUREOP alpha_ops[] = {
        D3DTOP_MODULATE, D3DTOP_ADD, D3DTOP_SUBTRACT, D3DTOP_ADDSIGNED, D3DTOP_ADDSMOOTH,
        D3DTOP_MODULATE2X, D3DTOP_BLENDTEXTUREALPHA, D3DTOP_LERP,
    };
    int frame, i, n;

    create_device("ff_texops", argc, argv);
    for (i = 0; i < 2; i++) {
        CHECK(IDirect3DDevice9_CreateTexture(g_dev, 8, 8, 1, 0, D3DFMT_A8R8G8B8, D3DPOOL_MANAGED, &g_tex[i], NULL));
        fill(g_tex[i], i);
        CHECK(IDirect3DDevice9_SetSamplerState(g_dev, i, D3DSAMP_MINFILTER, D3DTEXF_POINT));
        CHECK(IDirect3DDevice9_SetSamplerState(g_dev, i, D3DSAMP_MAGFILTER, D3DTEXF_POINT));
        CHECK(IDirect3DDevice9_SetSamplerState(g_dev, i, D3DSAMP_MIPFILTER, D3DTEXF_NONE));
    }
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_LIGHTING, FALSE));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_ZENABLE, D3DZB_FALSE));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_CULLMODE, D3DCULL_NONE));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_TEXTUREFACTOR, 0x9050c0a0));
    CHECK(IDirect3DDevice9_SetFVF(g_dev, FVF));

    for (frame = 0; frame < 2; frame++) {
        CHECK(IDirect3DDevice9_Clear(g_dev, 0, NULL, D3DCLEAR_TARGET, D3DCOLOR_XRGB(0x10, 0x18, 0x20), 1.0f, 0));
        CHECK(IDirect3DDevice9_BeginScene(g_dev));
        CHECK(IDirect3DDevice9_SetTexture(g_dev, 0, (IDirect3DBaseTexture9 *)g_tex[0]));
        CHECK(IDirect3DDevice9_SetTexture(g_dev, 1, (IDirect3DBaseTexture9 *)g_tex[1]));
        n = 0;
        if (frame == 0) {
            /* 22 colour ops: TEXTURE op DIFFUSE; alpha = texture alpha */
            for (i = 0; i < (int)(sizeof colour_ops / sizeof colour_ops[0]); i++) {
                reset_stages();
                ts(0, D3DTSS_COLOROP, colour_ops[i]);
                ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
                ts(0, D3DTSS_COLORARG0, D3DTA_TFACTOR);
                cell(n++, kDiffuse[i & 3], 0xff000000);
            }
            /* 8 alpha ops, shown as grey by stage 1 */
            for (i = 0; i < (int)(sizeof alpha_ops / sizeof alpha_ops[0]); i++) {
                reset_stages();
                ts(0, D3DTSS_COLOROP, D3DTOP_SELECTARG1);
                ts(0, D3DTSS_ALPHAOP, alpha_ops[i]);
                ts(0, D3DTSS_ALPHAARG2, D3DTA_DIFFUSE);
                ts(0, D3DTSS_ALPHAARG0, D3DTA_TFACTOR);
                ts(1, D3DTSS_COLOROP, D3DTOP_SELECTARG1);
                ts(1, D3DTSS_COLORARG1, D3DTA_CURRENT | D3DTA_ALPHAREPLICATE);
                cell(n++, kDiffuse[i & 3], 0xff000000);
            }
            /* argument modifiers */
            reset_stages();                                   /* COMPLEMENT texture x diffuse */
            ts(0, D3DTSS_COLORARG1, D3DTA_TEXTURE | D3DTA_COMPLEMENT);
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            cell(n++, 0xffe0c0a0, 0);
            reset_stages();                                   /* texture x ALPHAREPLICATE diffuse */
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE | D3DTA_ALPHAREPLICATE);
            cell(n++, 0x90ffffff, 0);
            reset_stages();                                   /* TFACTOR + texture alpha complement */
            ts(0, D3DTSS_COLOROP, D3DTOP_ADD);
            ts(0, D3DTSS_COLORARG1, D3DTA_TFACTOR);
            ts(0, D3DTSS_COLORARG2, D3DTA_TEXTURE | D3DTA_ALPHAREPLICATE | D3DTA_COMPLEMENT);
            cell(n++, 0xffffffff, 0);
            reset_stages();                                   /* SPECULAR argument, subtract */
            ts(0, D3DTSS_COLOROP, D3DTOP_SUBTRACT);
            ts(0, D3DTSS_COLORARG1, D3DTA_SPECULAR);
            ts(0, D3DTSS_COLORARG2, D3DTA_TEXTURE);
            cell(n++, 0xffffffff, 0x00f0a050);
            reset_stages();                                   /* stage 1 tex1 with coord set 1 */
            ts(0, D3DTSS_COLOROP, D3DTOP_SELECTARG2);
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            ts(1, D3DTSS_COLOROP, D3DTOP_MODULATE);
            ts(1, D3DTSS_ALPHAOP, D3DTOP_SELECTARG1);
            cell(n++, 0xffc0c0c0, 0);
            reset_stages();                                   /* stage 1 tex1 with coord set 0 */
            ts(0, D3DTSS_COLOROP, D3DTOP_SELECTARG2);
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            ts(1, D3DTSS_COLOROP, D3DTOP_MODULATE);
            ts(1, D3DTSS_TEXCOORDINDEX, 0);
            cell(n++, 0xffc0c0c0, 0);
        } else {
            /* 0: tex0 x diffuse, then x tex1 */
            reset_stages();
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            ts(1, D3DTSS_COLOROP, D3DTOP_MODULATE2X);
            cell(n++, 0xffa0c0e0, 0);
            /* 1: tex0 -> TEMP, stage 1 selects tex1, stage 2 adds TEMP */
            reset_stages();
            ts(0, D3DTSS_COLOROP, D3DTOP_SELECTARG1);
            ts(0, D3DTSS_RESULTARG, D3DTA_TEMP);
            ts(1, D3DTSS_COLOROP, D3DTOP_MODULATE);
            ts(1, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            ts(2, D3DTSS_COLOROP, D3DTOP_ADDSIGNED);
            ts(2, D3DTSS_COLORARG1, D3DTA_CURRENT);
            ts(2, D3DTSS_COLORARG2, D3DTA_TEMP);
            cell(n++, 0xff808080, 0);
            /* 2: BLENDCURRENTALPHA: current alpha from tex1 of stage 0? (alpha of diffuse) */
            reset_stages();
            ts(0, D3DTSS_COLOROP, D3DTOP_SELECTARG1);
            ts(0, D3DTSS_ALPHAOP, D3DTOP_SELECTARG1);
            ts(0, D3DTSS_ALPHAARG1, D3DTA_DIFFUSE);
            ts(1, D3DTSS_COLOROP, D3DTOP_BLENDCURRENTALPHA);
            ts(1, D3DTSS_COLORARG1, D3DTA_CURRENT);
            ts(1, D3DTSS_COLORARG2, D3DTA_TEXTURE);
            cell(n++, 0x60ffffff, 0);
            /* 3: BLENDTEXTUREALPHA of tex1 over current */
            reset_stages();
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            ts(1, D3DTSS_COLOROP, D3DTOP_BLENDTEXTUREALPHA);
            cell(n++, 0xff40c0ff, 0);
            /* 4: three stages, last MODULATE2X with TFACTOR */
            reset_stages();
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            ts(1, D3DTSS_COLOROP, D3DTOP_ADD);
            ts(2, D3DTSS_COLOROP, D3DTOP_MODULATE2X);
            ts(2, D3DTSS_COLORARG1, D3DTA_TFACTOR);
            cell(n++, 0xff604020, 0);
            /* 5: DOTPRODUCT3 of tex1 and current, then modulate with diffuse */
            reset_stages();
            ts(0, D3DTSS_COLOROP, D3DTOP_SELECTARG1);
            ts(1, D3DTSS_COLOROP, D3DTOP_DOTPRODUCT3);
            ts(2, D3DTSS_COLOROP, D3DTOP_MODULATE);
            ts(2, D3DTSS_COLORARG1, D3DTA_DIFFUSE);
            cell(n++, 0xffffc080, 0);
            /* 6: LERP(tex1, current, TFACTOR) */
            reset_stages();
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            ts(1, D3DTSS_COLOROP, D3DTOP_LERP);
            ts(1, D3DTSS_COLORARG0, D3DTA_TEXTURE);
            ts(1, D3DTSS_COLORARG1, D3DTA_CURRENT);
            ts(1, D3DTSS_COLORARG2, D3DTA_TFACTOR);
            cell(n++, 0xffe0e0e0, 0);
            /* 7: MULTIPLYADD: TEMP + current x tex1 */
            reset_stages();
            ts(0, D3DTSS_COLOROP, D3DTOP_SELECTARG1);
            ts(0, D3DTSS_COLORARG1, D3DTA_DIFFUSE);
            ts(0, D3DTSS_RESULTARG, D3DTA_TEMP);
            ts(1, D3DTSS_COLOROP, D3DTOP_MULTIPLYADD);
            ts(1, D3DTSS_COLORARG0, D3DTA_TEMP);
            ts(1, D3DTSS_COLORARG1, D3DTA_CURRENT);
            ts(1, D3DTSS_COLORARG2, D3DTA_TEXTURE);
            cell(n++, 0xff302010, 0);
            /* 8: alpha: stage 0 alpha = tex0 a, stage 1 ALPHAOP DISABLE keeps it, stage 2 shows it */
            reset_stages();
            ts(1, D3DTSS_COLOROP, D3DTOP_ADD);
            ts(1, D3DTSS_ALPHAOP, D3DTOP_DISABLE);
            ts(2, D3DTSS_COLOROP, D3DTOP_MODULATE);
            ts(2, D3DTSS_COLORARG1, D3DTA_CURRENT | D3DTA_ALPHAREPLICATE);
            ts(2, D3DTSS_COLORARG2, D3DTA_CURRENT);
            cell(n++, 0xff808080, 0);
            /* 9: alpha ops across stages: tex0.a x tex1.a, complement, shown in stage 2 */
            reset_stages();
            ts(1, D3DTSS_COLOROP, D3DTOP_SELECTARG1);
            ts(1, D3DTSS_ALPHAOP, D3DTOP_MODULATE);
            ts(1, D3DTSS_ALPHAARG1, D3DTA_TEXTURE | D3DTA_COMPLEMENT);
            ts(2, D3DTSS_COLOROP, D3DTOP_BLENDCURRENTALPHA);
            ts(2, D3DTSS_COLORARG1, D3DTA_CURRENT);
            ts(2, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            cell(n++, 0xff2040ff, 0);
            /* 10: SPECULARENABLE adds the specular colour after the stages */
            reset_stages();
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_SPECULARENABLE, TRUE));
            cell(n++, 0xff808080, 0x00403020);
            /* 11: TFACTOR MODULATE4X with diffuse, then ADDSMOOTH with tex1 */
            reset_stages();
            ts(0, D3DTSS_COLOROP, D3DTOP_MODULATE4X);
            ts(0, D3DTSS_COLORARG1, D3DTA_TFACTOR);
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            ts(1, D3DTSS_COLOROP, D3DTOP_ADDSMOOTH);
            cell(n++, 0xff304050, 0);
            /* 12: TEMP used as arg before any stage wrote it (reads 0): ADD current TEMP */
            reset_stages();
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            ts(1, D3DTSS_COLOROP, D3DTOP_ADD);
            ts(1, D3DTSS_COLORARG1, D3DTA_TEMP);
            ts(1, D3DTSS_COLORARG2, D3DTA_CURRENT);
            cell(n++, 0xff808080, 0);
            /* 13: stage 0 SUBTRACT tex1-like: tex0 - diffuse, stage1 BLENDDIFFUSEALPHA */
            reset_stages();
            ts(0, D3DTSS_COLOROP, D3DTOP_SUBTRACT);
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            ts(1, D3DTSS_COLOROP, D3DTOP_BLENDDIFFUSEALPHA);
            cell(n++, 0x70204060, 0);
            /* 14: stage1 BLENDFACTORALPHA, stage 2 MODULATEALPHA_ADDCOLOR with diffuse */
            reset_stages();
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            ts(1, D3DTSS_COLOROP, D3DTOP_BLENDFACTORALPHA);
            ts(2, D3DTSS_COLOROP, D3DTOP_MODULATEALPHA_ADDCOLOR);
            ts(2, D3DTSS_COLORARG1, D3DTA_CURRENT);
            ts(2, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            cell(n++, 0x50303030, 0);
            /* 15: LERP with TEXTURE|ALPHAREPLICATE as arg0 in stage 1 and TEMP arg2 */
            reset_stages();
            ts(0, D3DTSS_COLOROP, D3DTOP_MODULATE);
            ts(0, D3DTSS_COLORARG2, D3DTA_DIFFUSE);
            ts(0, D3DTSS_RESULTARG, D3DTA_TEMP);
            ts(1, D3DTSS_COLOROP, D3DTOP_LERP);
            ts(1, D3DTSS_COLORARG0, D3DTA_TEXTURE | D3DTA_ALPHAREPLICATE);
            ts(1, D3DTSS_COLORARG1, D3DTA_TEXTURE);
            ts(1, D3DTSS_COLORARG2, D3DTA_TEMP);
            cell(n++, 0xffff8040, 0);
        }
        CHECK(IDirect3DDevice9_EndScene(g_dev));
        save_frame(frame);
        CHECK(IDirect3DDevice9_Present(g_dev, NULL, NULL, NULL, NULL));
    }
    IDirect3DTexture9_Release(g_tex[0]);
    IDirect3DTexture9_Release(g_tex[1]);
    destroy_device();
    return 0;
}
