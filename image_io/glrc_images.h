/* The C interface of glrefcheck's image plugin (glrefcheck_images.so), the one library that
 * links OpenImageIO. It is opened with dlopen when the first image is written, so that a
 * glrefcheck process that writes none does not load OpenImageIO's ~260 shared libraries
 * (0.4 s at every start). Plain C types only: the plugin and the program may be built apart. */
#ifndef GLRC_IMAGES_H
#define GLRC_IMAGES_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Raised whenever a function below or its meaning changes; the loader refuses a plugin whose
 * glrc_images_entry() gives another version (a stale build). */
#define GLRC_IMAGES_ABI_VERSION 2

/* Every image write_image writes names glrefcheck as its "Software" (a PNG tEXt chunk, an EXR
 * header attribute, both ahead of the pixels): a run, merge or campaign replaces in its cases/
 * only images that carry it, never a person's picture put there (version 2). */
#define GLRC_IMAGES_SOFTWARE "glrefcheck"

/* The name the loader looks for, and the symbol it looks up in it. */
#define GLRC_IMAGES_PLUGIN_FILE "glrefcheck_images.so"
#define GLRC_IMAGES_ENTRY "glrc_images_entry"

/* How write_image stores the samples in the file. */
enum glrc_images_storage { GLRC_IMAGES_UINT8 = 0, GLRC_IMAGES_FLOAT = 1 };

/* Horizontal alignment of render_text's x. */
enum glrc_images_align { GLRC_IMAGES_LEFT = 0, GLRC_IMAGES_CENTRE = 1, GLRC_IMAGES_RIGHT = 2 };

/* Every function that can fail returns 1 on success and 0 on failure, writing a one-line,
 * NUL-terminated reason (truncated to error_size bytes) into `error` when error_size > 0. None
 * throws or aborts. Images are row 0 at the top, `channels` floats per pixel, interleaved. */
struct glrc_images_api {
  /* GLRC_IMAGES_ABI_VERSION of the plugin's build; the loader checks it before anything else. */
  int abi_version;

  /* Writes width x height pixels of `channels` floats (1: channel "Y"; 3: "R", "G", "B") to
   * `path`, the format chosen by its extension (.png, .exr, ...), stored as `storage` (UINT8
   * maps 0..1 to 0..255), its "Software" GLRC_IMAGES_SOFTWARE. `description` (NULL: none)
   * goes into the file's ImageDescription, `compression` (NULL: the format's default) into its
   * "compression" attribute. */
  int (*write_image)(const char* path, int width, int height, int channels, const float* pixels,
                     int storage, const char* description, const char* compression, char* error,
                     size_t error_size);

  /* Sets *width and *height to the extent of `text` drawn at `size` pixels in the TrueType font
   * `font` (a name found in OpenImageIO's font path, or a file). */
  int (*text_size)(const char* text, int size, const char* font, int* width, int* height,
                   char* error, size_t error_size);

  /* Draws `text` with its baseline at y and x aligned by `align` (a glrc_images_align) into the
   * width x height RGB float buffer `rgb`, in `colour` (3 floats). Pixels outside are clipped. */
  int (*render_text)(float* rgb, int width, int height, int x, int y, const char* text, int size,
                     const char* font, const float* colour, int align, char* error,
                     size_t error_size);

  /* 1 if the font `font` can be loaded (text_size would work), else 0. */
  int (*font_loads)(const char* font);
};

/* The plugin's one exported symbol (GLRC_IMAGES_ENTRY): its functions, valid for as long as
 * the plugin stays loaded. */
const struct glrc_images_api* glrc_images_entry(void);

#ifdef __cplusplus
}
#endif

#endif
