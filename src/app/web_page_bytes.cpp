// The bytes of luz.html, the page web/ builds with Emscripten, included by the assembler
// (.incbin) from the file CMake names (LUZ_WEB_HTML); compiled alone, after the page is built,
// so that the rest of the command's code need not wait for the web build.
#ifdef LUZ_WEB_HTML
asm(".pushsection .rodata\n"
    ".global luz_web_html_begin\n"
    "luz_web_html_begin:\n"
    ".incbin \"" LUZ_WEB_HTML
    "\"\n"
    ".global luz_web_html_end\n"
    "luz_web_html_end:\n"
    ".popsection\n");
#endif
