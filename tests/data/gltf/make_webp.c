/* Writes the WebP test images of this directory (PROVENANCE.md) with libwebp:
   gcc make_webp.c $(pkg-config --cflags --libs libwebp) -o make_webp && ./make_webp */
#include <stdio.h>
#include <stdlib.h>
#include <webp/encode.h>
int main(void) {
    /* 4x2 lossless RGBA: red, green, blue, white / black, grey, half-transparent yellow, clear */
    unsigned char px[4 * 2 * 4] = {255,0,0,255, 0,255,0,255, 0,0,255,255, 255,255,255,255,
                                   0,0,0,255, 128,128,128,255, 255,255,0,128, 0,0,0,0};
    unsigned char* out = NULL;
    size_t n = WebPEncodeLosslessRGBA(px, 4, 2, 16, &out);
    FILE* f = fopen("quadrants_alpha.webp", "wb"); fwrite(out, 1, n, f); fclose(f); WebPFree(out);
    /* 16x16 lossy RGB: a gradient */
    unsigned char rgb[16 * 16 * 3];
    for (int y = 0; y < 16; ++y) for (int x = 0; x < 16; ++x) {
        unsigned char* p = rgb + (y * 16 + x) * 3; p[0] = x * 16; p[1] = y * 16; p[2] = 128; }
    n = WebPEncodeRGB(rgb, 16, 16, 48, 90, &out);
    f = fopen("gradient.webp", "wb"); fwrite(out, 1, n, f); fclose(f); WebPFree(out);
    return 0;
}
