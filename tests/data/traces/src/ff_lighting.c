/*
 * ff_lighting.c - fixed-function vertex lighting (no shaders).
 *
 * A UV sphere (XYZ|NORMAL|DIFFUSE|SPECULAR|TEX1, vertex + 16-bit index buffer, DrawIndexedPrimitive)
 * drawn in a 3x3 grid of 85x85 viewports, each cell one lighting setup, z-buffered, untextured.
 *  frame 0: lights: directional; point with linear+quadratic attenuation; point whose Range cuts the
 *           sphere; spot (falloff 1); spot (falloff 4) plus a dim directional; specular with
 *           LOCALVIEWER on; the same with LOCALVIEWER off; coloured specular of a point light;
 *           directional + point + spot together with light ambient.
 *  frame 1: COLORVERTEX and the material sources: DIFFUSE from COLOR1; COLORVERTEX off; AMBIENT from
 *           COLOR2; EMISSIVE from COLOR1; SPECULAR from COLOR1; DIFFUSE from COLOR2; a world scaled
 *           by 0.5 without NORMALIZENORMALS; the same with it; emissive + AMBIENT, no light.
 */
#include "sphere.h"

static void light_dir(DWORD i, D3DCOLORVALUE diffuse, D3DCOLORVALUE specular, vec3 dir)
{
    D3DLIGHT9 l;
    memset(&l, 0, sizeof l);
    l.Type = D3DLIGHT_DIRECTIONAL;
    l.Diffuse = diffuse; l.Specular = specular;
    l.Direction.x = dir.x; l.Direction.y = dir.y; l.Direction.z = dir.z;
    CHECK(IDirect3DDevice9_SetLight(g_dev, i, &l));
    CHECK(IDirect3DDevice9_LightEnable(g_dev, i, TRUE));
}

static void light_point(DWORD i, D3DCOLORVALUE diffuse, D3DCOLORVALUE specular, vec3 pos, float range,
                        float a0, float a1, float a2)
{
    D3DLIGHT9 l;
    memset(&l, 0, sizeof l);
    l.Type = D3DLIGHT_POINT;
    l.Diffuse = diffuse; l.Specular = specular;
    l.Position.x = pos.x; l.Position.y = pos.y; l.Position.z = pos.z;
    l.Range = range; l.Attenuation0 = a0; l.Attenuation1 = a1; l.Attenuation2 = a2;
    CHECK(IDirect3DDevice9_SetLight(g_dev, i, &l));
    CHECK(IDirect3DDevice9_LightEnable(g_dev, i, TRUE));
}

static void light_spot(DWORD i, D3DCOLORVALUE diffuse, vec3 pos, vec3 dir, float theta, float phi,
                       float falloff, D3DCOLORVALUE ambient)
{
    D3DLIGHT9 l;
    memset(&l, 0, sizeof l);
    l.Type = D3DLIGHT_SPOT;
    l.Diffuse = diffuse; l.Ambient = ambient;
    l.Position.x = pos.x; l.Position.y = pos.y; l.Position.z = pos.z;
    l.Direction.x = dir.x; l.Direction.y = dir.y; l.Direction.z = dir.z;
    l.Range = 20.0f; l.Attenuation0 = 1.0f;
    l.Theta = theta; l.Phi = phi; l.Falloff = falloff;
    CHECK(IDirect3DDevice9_SetLight(g_dev, i, &l));
    CHECK(IDirect3DDevice9_LightEnable(g_dev, i, TRUE));
}

static void reset_cell(const D3DMATERIAL9 *m)
{
    DWORD i;
    D3DMATRIX world = mat_identity();
    for (i = 0; i < 4; i++)
        CHECK(IDirect3DDevice9_LightEnable(g_dev, i, FALSE));
    CHECK(IDirect3DDevice9_SetMaterial(g_dev, m));
    CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_WORLD, &world));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_AMBIENT, 0xff202020));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_SPECULARENABLE, FALSE));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_LOCALVIEWER, TRUE));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_COLORVERTEX, FALSE));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_DIFFUSEMATERIALSOURCE, D3DMCS_COLOR1));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_SPECULARMATERIALSOURCE, D3DMCS_COLOR2));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_AMBIENTMATERIALSOURCE, D3DMCS_MATERIAL));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_EMISSIVEMATERIALSOURCE, D3DMCS_MATERIAL));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_NORMALIZENORMALS, FALSE));
}

int main(int argc, char **argv)
{
    IDirect3DVertexBuffer9 *vb;
    IDirect3DIndexBuffer9 *ib;
    D3DMATERIAL9 m;
    D3DMATRIX view, proj;
    const D3DCOLORVALUE white = rgba(1, 1, 1, 1), black = rgba(0, 0, 0, 0);
    int frame, c;

    create_device("ff_lighting", argc, argv);
    create_sphere(&vb, &ib);
    view = mat_look_at_lh(v3(0, 0.5f, -3.2f), v3(0, 0, 0), v3(0, 1, 0));
    proj = mat_perspective_fov_lh(3.14159265f / 4, 1.0f, 1.0f, 10.0f);
    CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_VIEW, &view));
    CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_PROJECTION, &proj));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_ZENABLE, D3DZB_TRUE));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_CULLMODE, D3DCULL_NONE));
    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_LIGHTING, TRUE));
    CHECK(IDirect3DDevice9_SetFVF(g_dev, FVF_SPHERE));
    CHECK(IDirect3DDevice9_SetStreamSource(g_dev, 0, vb, 0, sizeof(SphereVertex)));
    CHECK(IDirect3DDevice9_SetIndices(g_dev, ib));
    CHECK(IDirect3DDevice9_SetTextureStageState(g_dev, 0, D3DTSS_COLOROP, D3DTOP_SELECTARG1));
    CHECK(IDirect3DDevice9_SetTextureStageState(g_dev, 0, D3DTSS_COLORARG1, D3DTA_DIFFUSE));
    CHECK(IDirect3DDevice9_SetTextureStageState(g_dev, 0, D3DTSS_ALPHAOP, D3DTOP_SELECTARG1));
    CHECK(IDirect3DDevice9_SetTextureStageState(g_dev, 0, D3DTSS_ALPHAARG1, D3DTA_DIFFUSE));

    memset(&m, 0, sizeof m);
    m.Diffuse = rgba(0.8f, 0.6f, 0.4f, 1.0f);
    m.Ambient = rgba(0.3f, 0.3f, 0.5f, 1.0f);
    m.Specular = rgba(1.0f, 1.0f, 1.0f, 1.0f);
    m.Power = 16.0f;

    for (frame = 0; frame < 2; frame++) {
        clear_all(D3DCOLOR_XRGB(0x20, 0x20, 0x30));
        CHECK(IDirect3DDevice9_BeginScene(g_dev));
        for (c = 0; c < 9; c++) {
            D3DMATERIAL9 cm = m;
            cell_viewport(c % 3, c / 3, 85);
            reset_cell(&m);
            if (frame == 0) {
                switch (c) {
                case 0:
                    light_dir(0, rgba(1, 1, 1, 1), black, v3(-0.6f, -0.5f, 0.6f));
                    break;
                case 1:
                    light_point(0, rgba(1, 0.9f, 0.8f, 1), black, v3(1.2f, 1.0f, -1.5f), 10.0f, 0.0f, 0.3f, 0.15f);
                    break;
                case 2:
                    light_point(0, rgba(0.9f, 1, 0.9f, 1), black, v3(-0.8f, 0.4f, -1.6f), 2.0f, 1.0f, 0.0f, 0.0f);
                    break;
                case 3:
                    light_spot(0, white, v3(0, 0, -3), v3(0.1f, 0.05f, 1), 0.25f, 0.7f, 1.0f, black);
                    break;
                case 4:
                    light_spot(0, rgba(1, 0.8f, 0.5f, 1), v3(-1, 1, -3), v3(0.3f, -0.3f, 1), 0.2f, 0.8f, 4.0f, black);
                    light_dir(1, rgba(0.1f, 0.2f, 0.4f, 1), black, v3(0, -1, 0));
                    break;
                case 5:
                case 6:
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_SPECULARENABLE, TRUE));
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_LOCALVIEWER, c == 5));
                    light_dir(0, rgba(0.7f, 0.7f, 0.7f, 1), white, v3(-0.5f, -0.4f, 0.8f));
                    break;
                case 7:
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_SPECULARENABLE, TRUE));
                    cm.Power = 40.0f;
                    CHECK(IDirect3DDevice9_SetMaterial(g_dev, &cm));
                    light_point(0, rgba(0.6f, 0.6f, 0.6f, 1), rgba(0.2f, 0.6f, 1, 1), v3(0.5f, 1.5f, -2.0f), 8.0f,
                                0.5f, 0.1f, 0.0f);
                    break;
                case 8:
                    light_dir(0, rgba(0.3f, 0.3f, 0.3f, 1), black, v3(1, 0, 0.3f));
                    light_point(1, rgba(0.8f, 0.2f, 0.2f, 1), black, v3(-1.5f, 0, -1), 6.0f, 0.3f, 0.2f, 0.0f);
                    light_spot(2, rgba(0.2f, 0.8f, 0.2f, 1), v3(0, 2.5f, -1.5f), v3(0, -1, 0.6f), 0.4f, 1.0f, 1.0f,
                               rgba(0.1f, 0.1f, 0.3f, 1));
                    break;
                }
            } else {
                light_dir(0, rgba(0.9f, 0.9f, 0.9f, 1), rgba(1, 1, 1, 1), v3(-0.5f, -0.5f, 0.7f));
                CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_COLORVERTEX, TRUE));
                switch (c) {
                case 0: break;
                case 1: CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_COLORVERTEX, FALSE)); break;
                case 2:
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_DIFFUSEMATERIALSOURCE, D3DMCS_MATERIAL));
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_AMBIENTMATERIALSOURCE, D3DMCS_COLOR2));
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_AMBIENT, 0xffa0a0a0));
                    break;
                case 3:
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_DIFFUSEMATERIALSOURCE, D3DMCS_MATERIAL));
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_EMISSIVEMATERIALSOURCE, D3DMCS_COLOR1));
                    break;
                case 4:
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_DIFFUSEMATERIALSOURCE, D3DMCS_MATERIAL));
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_SPECULARMATERIALSOURCE, D3DMCS_COLOR1));
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_SPECULARENABLE, TRUE));
                    break;
                case 5:
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_DIFFUSEMATERIALSOURCE, D3DMCS_COLOR2));
                    break;
                case 6:
                case 7: {
                    D3DMATRIX w = mat_scaling(0.5f, 0.5f, 0.5f);
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_COLORVERTEX, FALSE));
                    CHECK(IDirect3DDevice9_SetTransform(g_dev, D3DTS_WORLD, &w));
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_NORMALIZENORMALS, c == 7));
                    break;
                }
                case 8:
                    CHECK(IDirect3DDevice9_LightEnable(g_dev, 0, FALSE));
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_COLORVERTEX, FALSE));
                    cm.Emissive = rgba(0.2f, 0.1f, 0.0f, 1);
                    CHECK(IDirect3DDevice9_SetMaterial(g_dev, &cm));
                    CHECK(IDirect3DDevice9_SetRenderState(g_dev, D3DRS_AMBIENT, 0xff806040));
                    break;
                }
            }
            draw_sphere();
        }
        CHECK(IDirect3DDevice9_EndScene(g_dev));
        save_frame(frame);
        CHECK(IDirect3DDevice9_Present(g_dev, NULL, NULL, NULL, NULL));
    }
    IDirect3DVertexBuffer9_Release(vb);
    IDirect3DIndexBuffer9_Release(ib);
    destroy_device();
    return 0;
}
