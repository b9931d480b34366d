// The OpenImageIO side of image_codec.h: the only code that calls OpenImageIO, built as the
// module sm2emu_image_io that the runtime dlopen()s on the first image read or write.
#include <OpenImageIO/imageio.h>

#include <memory>

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

constexpr Functions kFunctions{kAbiVersion, sizeof(Functions), open_image, read_image, close_image, write_image};

}  // namespace

extern "C" __attribute__((visibility("default"))) const Functions* sm2emu_image_codec_v1() { return &kFunctions; }
