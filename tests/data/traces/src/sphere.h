/*
 * sphere.h - a UV sphere (radius 1, SLICES x STACKS quads) for the fixed-function trace programs:
 * position, normal, diffuse and specular colours made from the position, and (u, v).
 */
#ifndef TRACES_SPHERE_H
#define TRACES_SPHERE_H
#include "common.h"

#define SLICES 16
#define STACKS 12
#define SPHERE_VERTS ((SLICES + 1) * (STACKS + 1))
#define SPHERE_INDICES (SLICES * STACKS * 6)

typedef struct { float x, y, z, nx, ny, nz; DWORD diffuse, specular; float u, v; } SphereVertex;
#define FVF_SPHERE (D3DFVF_XYZ | D3DFVF_NORMAL | D3DFVF_DIFFUSE | D3DFVF_SPECULAR | D3DFVF_TEX1)

static void create_sphere(IDirect3DVertexBuffer9 **vb, IDirect3DIndexBuffer9 **ib)
{
    SphereVertex *v;
    WORD *idx;
    int i, j, k = 0;
    CHECK(IDirect3DDevice9_CreateVertexBuffer(g_dev, SPHERE_VERTS * sizeof(SphereVertex), D3DUSAGE_WRITEONLY,
                                              FVF_SPHERE, D3DPOOL_MANAGED, vb, NULL));
    CHECK(IDirect3DDevice9_CreateIndexBuffer(g_dev, SPHERE_INDICES * sizeof(WORD), D3DUSAGE_WRITEONLY,
                                             D3DFMT_INDEX16, D3DPOOL_MANAGED, ib, NULL));
    CHECK(IDirect3DVertexBuffer9_Lock(*vb, 0, 0, (void **)&v, 0));
    for (j = 0; j <= STACKS; j++) {
        float th = 3.14159265f * j / STACKS;
        for (i = 0; i <= SLICES; i++) {
            float ph = 2 * 3.14159265f * i / SLICES;
            SphereVertex *p = &v[j * (SLICES + 1) + i];
            p->nx = sinf(th) * cosf(ph);
            p->ny = cosf(th);
            p->nz = sinf(th) * sinf(ph);
            p->x = p->nx; p->y = p->ny; p->z = p->nz;
            p->diffuse = D3DCOLOR_ARGB(0xc0, (int)(127.5f + 127.5f * p->x), (int)(127.5f + 127.5f * p->y), 0x60);
            p->specular = D3DCOLOR_ARGB(0x80, 0x40, (int)(127.5f - 127.5f * p->x), (int)(127.5f + 127.5f * p->z));
            p->u = (float)i / SLICES;
            p->v = (float)j / STACKS;
        }
    }
    CHECK(IDirect3DVertexBuffer9_Unlock(*vb));
    CHECK(IDirect3DIndexBuffer9_Lock(*ib, 0, 0, (void **)&idx, 0));
    for (j = 0; j < STACKS; j++)
        for (i = 0; i < SLICES; i++) {
            WORD a = j * (SLICES + 1) + i, b = a + 1, c = a + SLICES + 1, d = c + 1;
            idx[k++] = a; idx[k++] = b; idx[k++] = c;
            idx[k++] = b; idx[k++] = d; idx[k++] = c;
        }
    CHECK(IDirect3DIndexBuffer9_Unlock(*ib));
}

static void draw_sphere(void)
{
    CHECK(IDirect3DDevice9_DrawIndexedPrimitive(g_dev, D3DPT_TRIANGLELIST, 0, 0, SPHERE_VERTS, 0,
                                                SPHERE_INDICES / 3));
}

/* a square viewport cell of the 256x256 back buffer */
static void cell_viewport(int col, int row, int size)
{
    D3DVIEWPORT9 vp = { (DWORD)(col * size), (DWORD)(row * size), (DWORD)size, (DWORD)size, 0.0f, 1.0f };
    CHECK(IDirect3DDevice9_SetViewport(g_dev, &vp));
}

/* Clear clears only the viewport: the whole target first */
static void clear_all(D3DCOLOR colour)
{
    D3DVIEWPORT9 vp = { 0, 0, WIDTH, HEIGHT, 0.0f, 1.0f };
    CHECK(IDirect3DDevice9_SetViewport(g_dev, &vp));
    CHECK(IDirect3DDevice9_Clear(g_dev, 0, NULL, D3DCLEAR_TARGET | D3DCLEAR_ZBUFFER, colour, 1.0f, 0));
}

static D3DCOLORVALUE rgba(float r, float g, float b, float a)
{
    D3DCOLORVALUE c = { r, g, b, a };
    return c;
}
#endif
