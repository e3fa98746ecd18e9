# Flags for our own targets only (third-party headers are included as system headers).
# -ffp-contract=off: no fused multiply-add contraction, so images are bit-reproducible
# across builds and hosts. No -march=native: built on an AVX-512 host, the binary would
# stop with SIGILL on hosts without AVX-512, and even -march=x86-64-v3 lets GCC and Clang
# contract a*b+c into FMA; Embree and llvmpipe choose the host's ISA at run time anyway.
add_library(pbrkit_flags INTERFACE)
target_compile_options(pbrkit_flags INTERFACE
  -Wall -Wextra -Werror -ffp-contract=off)
