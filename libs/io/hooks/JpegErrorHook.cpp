// libjpeg's default error handler ends the process: error_exit prints the message and calls
// exit(1). MRPT's CImage decodes a JPEG image embedded in a rawlog with that default handler,
// so a damaged JPEG in one frame made lodestone-slam or lodestone-inspect exit from inside
// MRPT (from a decoding thread, even), with libjpeg's text and without the run's outputs
// (found by tests/fuzz/fuzz_rawlog_gz).
//
// Compiled into each Lodestone executable (as the allocation hooks are, and for the same
// reason: only the executable comes first in the dynamic linker's lookup), this jpeg_std_error
// calls libjpeg's own and then installs an error_exit that throws the message as a
// std::runtime_error. The exception unwinds through libjpeg's frames (Debian builds it with
// unwind tables) into MRPT's deserializer, which reports it as a failed object: a read error
// naming the entry; the decoder's memory is released before the throw. Code that installs its
// own error_exit after jpeg_std_error (OpenCV) keeps it.
#include <dlfcn.h>

#include <cstddef>
#include <cstdio>  // jpeglib.h needs FILE and size_t declared first
#include <stdexcept>
#include <string>

#include <jpeglib.h>

namespace {
using StdError = jpeg_error_mgr* (*)(jpeg_error_mgr*);
using Destroy = void (*)(j_common_ptr);

[[noreturn]] void throwingErrorExit(j_common_ptr cinfo) {
    char text[JMSG_LENGTH_MAX] = {0};
    (*cinfo->err->format_message)(cinfo, text);
    // The caller never gets to destroy the decoder once error_exit has run: free its memory
    // pools now (jpeg_destroy leaves the struct safe to destroy again).
    // (Looked up, not linked: the executable does not depend on libjpeg; MRPT brought it in.)
    static const auto destroy = reinterpret_cast<Destroy>(dlsym(RTLD_DEFAULT, "jpeg_destroy"));
    if (destroy) destroy(cinfo);
    throw std::runtime_error(std::string("JPEG image: ") + text);
}
}  // namespace

extern "C" jpeg_error_mgr* jpeg_std_error(jpeg_error_mgr* err) {
    static const auto libjpeg = reinterpret_cast<StdError>(dlsym(RTLD_NEXT, "jpeg_std_error"));
    if (!libjpeg) throw std::runtime_error("libjpeg's jpeg_std_error not found");
    libjpeg(err);
    err->error_exit = throwingErrorExit;
    return err;
}
