# cmake -DWEB=web/ -DCORE=luz_core.js -DOUT=luz.html -P make_page.cmake: the one self-contained
# page — page.html with page.css, page.js and the worker (Emscripten's output, the WebAssembly
# inside it as base64, then worker.js) inlined.
file(READ ${WEB}/page.html page)
file(READ ${WEB}/page.css css)
file(READ ${WEB}/page.js js)
file(READ ${CORE} core)
file(READ ${WEB}/worker.js worker)
set(worker "${core}\n${worker}")
# Inside <script> an HTML parser would end the element at "</script" (and "<!--" changes its
# state): both written otherwise, the same in JavaScript.
foreach(var worker js)
  string(REPLACE "</script" "<\\/script" ${var} "${${var}}")
  string(REPLACE "<!--" "<\\!--" ${var} "${${var}}")
endforeach()
string(REPLACE "/*LUZ_CSS*/" "${css}" page "${page}")
string(REPLACE "/*LUZ_WORKER_JS*/" "${worker}" page "${page}")
string(REPLACE "/*LUZ_PAGE_JS*/" "${js}" page "${page}")
file(WRITE ${OUT} "${page}")
