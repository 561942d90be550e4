// Whether an image file was written to its end. A disk that fills up (or a file size limit)
// can cut a file short without the encoder noticing: OpenImageIO, libpng and stb do not check
// the last flush when they close the file. The render's writers rename a frame into place
// only when this says it is whole.
#pragma once

#include <string>

namespace pathlet {

// Without decoding the file, reading a few bytes of it: PNG ends with its IEND chunk, JPEG
// with its end-of-image marker; OpenEXR (single-part scan lines): every chunk the offset table
// names lies inside the file; TIFF: its first directory and every strip or tile it names do.
// Any other format (or layout): read_image reads it.
bool image_file_complete(const std::string& path);

}  // namespace pathlet
