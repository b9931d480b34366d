// D3D9 enum names against the values of d3d9types.h as printed in pipeline.md §16-§18.
#include <gtest/gtest.h>

#include <set>

#include "sm2/runtime/d3d9_names.h"
#include "sm2/runtime/texture.h"

namespace sm2::runtime {
namespace {

TEST(D3D9Names, RenderStatesByNameAndNumber) {
    // pipeline.md §16
    EXPECT_EQ(find_render_state("CULLMODE")->id, 22u);
    EXPECT_EQ(find_render_state("D3DRS_CULLMODE")->id, 22u);
    EXPECT_EQ(find_render_state("SRGBWRITEENABLE")->id, 194u);
    EXPECT_EQ(find_render_state("BLENDOPALPHA")->id, 209u);
    EXPECT_EQ(find_render_state(168u)->name, "COLORWRITEENABLE");
    EXPECT_EQ(find_render_state(36u)->kind, StateValueKind::Float);    // FOGSTART
    EXPECT_EQ(find_render_state(195u)->kind, StateValueKind::Float);   // DEPTHBIAS
    EXPECT_EQ(find_render_state(193u)->kind, StateValueKind::Color);   // BLENDFACTOR
    EXPECT_EQ(find_render_state(23u)->family, EnumFamily::Cmp);        // ZFUNC
    EXPECT_EQ(find_render_state("cullmode"), nullptr);                 // D3D spelling only
    // fixed-function and tessellator states are known but ignored with shaders (§16)
    EXPECT_TRUE(find_render_state("LIGHTING")->fixed_function);
    EXPECT_TRUE(find_render_state(184u)->fixed_function);  // ENABLEADAPTIVETESSELLATION
    EXPECT_FALSE(find_render_state("CULLMODE")->fixed_function);
    EXPECT_EQ(find_render_state(1u), nullptr);
    std::set<uint32_t> ids;
    for (const auto& s : render_states()) EXPECT_TRUE(ids.insert(s.id).second) << s.name;
}

TEST(D3D9Names, SamplerStates) {
    // pipeline.md §17
    EXPECT_EQ(find_sampler_state("ADDRESSW")->id, 3u);
    EXPECT_EQ(find_sampler_state("D3DSAMP_MAXANISOTROPY")->id, 10u);
    EXPECT_EQ(find_sampler_state(8u)->kind, StateValueKind::Float);  // MIPMAPLODBIAS
    EXPECT_EQ(find_sampler_state(6u)->family, EnumFamily::TextureFilter);
}

TEST(D3D9Names, EnumValues) {
    EXPECT_EQ(enum_value(EnumFamily::Cull, "NONE"), 1u);
    EXPECT_EQ(enum_value(EnumFamily::Cull, "D3DCULL_CCW"), 3u);
    EXPECT_EQ(enum_value(EnumFamily::Cmp, "GREATEREQUAL"), 7u);
    EXPECT_EQ(enum_value(EnumFamily::Blend, "INVBLENDFACTOR"), 15u);
    EXPECT_EQ(enum_value(EnumFamily::BlendOp, "REVSUBTRACT"), 3u);
    EXPECT_EQ(enum_value(EnumFamily::StencilOp, "DECR"), 8u);
    EXPECT_EQ(enum_value(EnumFamily::PrimitiveType, "TRIANGLEFAN"), 6u);
    EXPECT_EQ(enum_value(EnumFamily::DeclType, "D3DCOLOR"), 4u);
    EXPECT_EQ(enum_value(EnumFamily::DeclType, "D3DDECLTYPE_FLOAT16_4"), 16u);
    EXPECT_EQ(enum_value(EnumFamily::DeclUsage, "TEXCOORD"), 5u);
    EXPECT_EQ(enum_value(EnumFamily::TextureAddress, "MIRRORONCE"), 5u);
    EXPECT_EQ(enum_value(EnumFamily::TextureFilter, "ANISOTROPIC"), 3u);
    EXPECT_EQ(enum_value(EnumFamily::FogMode, "LINEAR"), 3u);
    EXPECT_EQ(enum_value(EnumFamily::ZBufferType, "USEW"), 2u);
    EXPECT_EQ(enum_value(EnumFamily::ClearFlags, "STENCIL"), 4u);
    EXPECT_EQ(enum_value(EnumFamily::ColorWrite, "ALPHA"), 8u);
    EXPECT_EQ(enum_value(EnumFamily::Bool, "TRUE"), 1u);
    EXPECT_EQ(enum_value(EnumFamily::CubeFace, "POSITIVE_Y"), 2u);              // d3d9types.h
    EXPECT_EQ(enum_value(EnumFamily::CubeFace, "D3DCUBEMAP_FACE_NEGATIVE_Z"), 5u);
    EXPECT_EQ(enum_value(EnumFamily::CubeFace, "NEGATIVE_Z"), static_cast<uint32_t>(CubeFace::NegativeZ));
    EXPECT_EQ(enum_value(EnumFamily::RenderState, "ZFUNC"), 23u);
    EXPECT_EQ(enum_value(EnumFamily::Cull, "SIDEWAYS"), std::nullopt);
    EXPECT_EQ(enum_value(EnumFamily::Cull, "D3DCMP_LESS"), std::nullopt);  // other family's prefix
    EXPECT_EQ(enum_name(EnumFamily::Cmp, 4), "LESSEQUAL");
    EXPECT_EQ(enum_name(EnumFamily::Cmp, 9), "");
    EXPECT_EQ(enum_prefix(EnumFamily::StencilOp), "D3DSTENCILOP_");
}

}  // namespace
}  // namespace sm2::runtime
