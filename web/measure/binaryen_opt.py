#!/usr/bin/env python3
"""Binaryen's optimiser (what `wasm-opt -Oz` runs) through libbinaryen's C API, for a binaryen
newer than Debian's (docs/web.md, "A lighter page"). PyPI's icpp-binaryen ships binaryen's own
libbinaryen.so; wasm-opt's command line is not in any registry this project reaches as a binary.
    pip install --target /tmp/icpp icpp-binaryen==116.0.1
    python3 web/measure/binaryen_opt.py /tmp/icpp/icpp_binaryen/lib/libbinaryen.so \
        web/dist/rigidlab_bg.wasm OUT.wasm 2 2      # optimize level, shrink level: -Oz is 2 2
Then gzip and zstd OUT.wasm as web/build.sh does, and write its size into index.html's
data-wasm-bytes."""
import ctypes as C
import sys
import time

# The features rustc's wasm32-unknown-unknown uses (the `target_features` section lists them too).
FEATURES = ["BulkMemory", "Multivalue", "MutableGlobals", "NontrappingFPToInt", "ReferenceTypes", "SignExt"]


class Written(C.Structure):
    _fields_ = [("binary", C.c_void_p), ("binaryBytes", C.c_size_t), ("sourceMap", C.c_char_p)]


def main():
    lib = C.CDLL(sys.argv[1])
    src, dst, opt, shrink = sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
    lib.BinaryenModuleRead.restype = C.c_void_p
    lib.BinaryenModuleRead.argtypes = [C.c_char_p, C.c_size_t]
    lib.BinaryenModuleGetFeatures.restype = C.c_uint32
    lib.BinaryenModuleGetFeatures.argtypes = [C.c_void_p]
    lib.BinaryenModuleSetFeatures.argtypes = [C.c_void_p, C.c_uint32]
    lib.BinaryenModuleOptimize.argtypes = [C.c_void_p]
    lib.BinaryenModuleValidate.argtypes = [C.c_void_p]
    lib.BinaryenModuleValidate.restype = C.c_bool
    lib.BinaryenModuleAllocateAndWrite.restype = Written
    lib.BinaryenModuleAllocateAndWrite.argtypes = [C.c_void_p, C.c_char_p]
    data = open(src, "rb").read()
    t0 = time.time()
    module = lib.BinaryenModuleRead(data, len(data))
    features = lib.BinaryenModuleGetFeatures(module)
    for name in FEATURES:
        fn = getattr(lib, "BinaryenFeature" + name)
        fn.restype = C.c_uint32
        features |= fn()
    lib.BinaryenModuleSetFeatures(module, features)
    lib.BinaryenSetOptimizeLevel(opt)
    lib.BinaryenSetShrinkLevel(shrink)
    lib.BinaryenSetDebugInfo(0)
    lib.BinaryenModuleOptimize(module)
    if not lib.BinaryenModuleValidate(module):
        sys.exit("binaryen_opt: the optimised module does not validate")
    out = lib.BinaryenModuleAllocateAndWrite(module, None)
    open(dst, "wb").write(C.string_at(out.binary, out.binaryBytes))
    print(f"{src}: {len(data)} bytes -> {dst}: {out.binaryBytes} bytes in {time.time() - t0:.0f} s")


if __name__ == "__main__":
    main()
