#!/bin/sh
# The AVX2 kernels' object (src/geometry/isa/query_avx2.cpp) may define, for the linker to share,
# nothing but its own code (whose names all hold luz_avx2) and the four entry points of
# geometry/query_isa.h: any other global or weak definition (an inline function of std compiled
# with AVX2) could be the copy the linker keeps for the portable code too — instructions a CPU
# without AVX2 lacks, and a function the portable code may no longer inline.
# Usage: query_avx2_symbols.sh OBJECT… (the library's objects; the kernels' one is picked by
# name).
for o in "$@"; do
    case "$o" in
    *query_avx2*)
        shared=$(nm -C --defined-only "$o" | awk '$2 ~ /^[TWVui]$/' |
            grep -v -e 'luz_avx2' -e ' luz::query::avx2::' -e ' [TWVui] _GLOBAL__' \
                -e ' V DW.ref.__gxx_personality')
        if [ -n "$shared" ]; then
            echo "$o defines for sharing:"
            echo "$shared"
            exit 1
        fi
        echo "$o: only luz_avx2 code and the entry points"
        exit 0
        ;;
    esac
done
echo "no query_avx2 object among the arguments" >&2
exit 1
