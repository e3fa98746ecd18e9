# Flags for our own targets only (third-party headers are included as system headers).
# -ffp-contract=off: no fused multiply-add contraction, so images are bit-reproducible
# across builds and hosts. No -march=native (see ../shared/PLATFORM.md).
add_library(pbrkit_flags INTERFACE)
target_compile_options(pbrkit_flags INTERFACE
  -Wall -Wextra -Werror -ffp-contract=off)
