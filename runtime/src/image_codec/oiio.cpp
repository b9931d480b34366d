// The OpenImageIO side of image_codec.h: the only code that calls OpenImageIO, built as the
// module sm2emu_image_io that the runtime dlopen()s on the first image read or write.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "image_codec.h"

namespace {

using namespace sm2::runtime::image_codec;

struct OpenReader {
    std::unique_ptr<OIIO::ImageInput> input;
    OIIO::ImageSpec spec;
};

PixelType pixel_type(const OIIO::TypeDesc& t) {
    switch (t.basetype) {
    case OIIO::TypeDesc::UINT8: return PixelType::U8;
    case OIIO::TypeDesc::UINT16: return PixelType::U16;
    case OIIO::TypeDesc::HALF: return PixelType::Half;
    case OIIO::TypeDesc::FLOAT: return PixelType::Float;
    default: return PixelType::Other;
    }
}

void* open_image(const char* path, Info* info, OpenStatus* status, std::string* error) {
    // Values as stored in the file: no premultiplication of PNG/TGA alpha on read.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    // create + open (rather than the static ImageInput::open) keeps the error on the object,
    // so a failed open leaves nothing in OpenImageIO's per-thread error string.
    auto reader = std::make_unique<OpenReader>();
    reader->input = OIIO::ImageInput::create(path);
    if (!reader->input) {
        *status = OpenStatus::NoReader;
        *error = OIIO::geterror();
        return nullptr;
    }
    if (!reader->input->open(path, reader->spec, config)) {
        *status = OpenStatus::CannotOpen;
        *error = reader->input->geterror();
        return nullptr;
    }
    *status = OpenStatus::Ok;
    info->width = reader->spec.width;
    info->height = reader->spec.height;
    info->depth = reader->spec.depth;
    info->channels = reader->spec.nchannels;
    info->type = pixel_type(reader->spec.format);
    return reader.release();
}

bool read_image(void* handle, int channels, float* pixels, std::string* error) {
    auto* reader = static_cast<OpenReader*>(handle);
    if (channels < 1 || channels > reader->spec.nchannels) {
        *error = "bad channel count";
        return false;
    }
    if (!reader->input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels)) {
        *error = reader->input->geterror();
        return false;
    }
    return true;
}

void close_image(void* handle) {
    auto* reader = static_cast<OpenReader*>(handle);
    reader->input->close();
    delete reader;
}

bool write_image(const char* path, uint32_t width, uint32_t height, bool eight_bit, const void* rgba,
                 std::string* error) {
    auto output = OIIO::ImageOutput::create(path);
    if (!output) {
        *error = "no writer for this file: " + OIIO::geterror();
        return false;
    }
    const OIIO::TypeDesc type = eight_bit ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
    OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 4, type);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // store the values as given, no premultiplication
    // OpenImageIO stamps EXR files with the wall-clock time (capDate) unless DateTime is given:
    // a fixed one keeps every output file byte-reproducible.
    spec.attribute("DateTime", "1970:01:01 00:00:00");
    if (!output->open(path, spec)) {
        *error = "cannot open for writing: " + output->geterror();
        return false;
    }
    if (!output->write_image(type, rgba) || !output->close()) {
        *error = "write failed: " + output->geterror();
        return false;
    }
    return true;
}

// A float RGBA image over the caller's pixels (read only: ImageBufAlgo never writes its inputs).
OIIO::ImageBuf wrap_rgba(uint32_t width, uint32_t height, const float* rgba) {
    const OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 4, OIIO::TypeDesc::FLOAT);
    return OIIO::ImageBuf(spec, const_cast<float*>(rgba));
}

bool compare_images(uint32_t width, uint32_t height, const float* a, const float* b, float fail_threshold,
                    float warn_threshold, CompareStats* stats, std::string* /*error*/) {
    const OIIO::ImageBuf image_a = wrap_rgba(width, height, a), image_b = wrap_rgba(width, height, b);
    // r.error is set when any pixel fails, not only when the comparison could not be made: the
    // errors that could stop it (sizes, channels, pixel types) are ruled out by the caller.
    const auto r = OIIO::ImageBufAlgo::compare(image_a, image_b, fail_threshold, warn_threshold);
    *stats = CompareStats{r.meanerror, r.rms_error, r.PSNR, r.maxerror, r.maxx, r.maxy, r.maxc,
                          static_cast<uint64_t>(r.nwarn), static_cast<uint64_t>(r.nfail)};
    return true;
}

bool heatmap(uint32_t width, uint32_t height, const float* a, const float* b, float scale, float* heat,
             std::string* error) {
    using namespace OIIO;
    const ImageBuf image_a = wrap_rgba(width, height, a), image_b = wrap_rgba(width, height, b);
    const ImageBuf largest = ImageBufAlgo::maxchan(ImageBufAlgo::absdiff(image_a, image_b));
    const ImageBuf scaled = ImageBufAlgo::div(largest, scale);
    const float black_to_red[] = {0, 0, 0, 1, 0, 0};
    ImageBuf rgb = ImageBufAlgo::color_map(scaled, 0, 2, 3, black_to_red);
    const int channel_order[] = {0, 1, 2, -1};
    const float opaque[] = {0, 0, 0, 1};
    const ImageBuf rgba = ImageBufAlgo::channels(rgb, 4, channel_order, opaque);
    if (rgba.has_error() || !rgba.initialized()) {
        *error = "heat map failed: " + OIIO::geterror();
        return false;
    }
    return rgba.get_pixels(rgba.roi(), TypeDesc::FLOAT, heat);
}

bool png_thumbnail(uint32_t width, uint32_t height, const float* rgba, uint32_t max_side, bool keep_peaks,
                   std::string* base64, std::string* error) {
    using namespace OIIO;
    const ImageBuf image = wrap_rgba(width, height, rgba);
    const double shrink = std::min(1.0, static_cast<double>(max_side) / std::max(width, height));
    const int w = std::max(1, static_cast<int>(width * shrink + 0.5)), h = std::max(1, static_cast<int>(height * shrink + 0.5));
    const ROI size(0, w, 0, h, 0, 1, 0, 4);
    ImageBuf small;
    if (keep_peaks) {
        // dilate: the largest value in a window as wide as a thumbnail pixel; then point samples.
        const int window = static_cast<int>(std::ceil(1.0 / shrink));
        small = ImageBufAlgo::resample(ImageBufAlgo::dilate(image, window, window), false, size);
    } else {
        small = ImageBufAlgo::resize(image, "", 0.0f, size);
    }
    std::vector<unsigned char> bytes;
    Filesystem::IOVecOutput memory(bytes);
    auto output = ImageOutput::create("thumbnail.png", &memory);
    ImageSpec spec(w, h, 4, TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (!output || small.has_error() || !output->open("thumbnail.png", spec) ||
        !output->write_image(TypeDesc::FLOAT, small.localpixels()) || !output->close()) {
        *error = "thumbnail failed: " + (output ? output->geterror() : OIIO::geterror());
        return false;
    }
    *base64 = Strutil::base64_encode(string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
    return true;
}

constexpr Functions kFunctions{kAbiVersion, sizeof(Functions), open_image,     read_image, close_image,
                               write_image, compare_images,    heatmap,        png_thumbnail};

}  // namespace

extern "C" __attribute__((visibility("default"))) const Functions* sm2emu_image_codec_v1() { return &kFunctions; }
