# Refuses, at configure time, compiler flags that would let a*b+c be fused
# into an FMA (or otherwise change float results): bitwise agreement between
# the exact accelerators rests on every float expression being evaluated as
# written. Flags are read in order, so a later -ffp-contract=off makes an
# earlier FMA-capable -march or -mfma safe again.
function(kappa_refuse_contracting_flags flags)
  separate_arguments(tokens UNIX_COMMAND "${flags}")
  # -march values whose instruction set has FMA (and "native", which may).
  set(fma_arches native haswell broadwell skylake skylake-avx512 cascadelake cooperlake cannonlake icelake-client
      icelake-server tigerlake rocketlake alderlake raptorlake meteorlake sapphirerapids graniterapids emeraldrapids
      znver1 znver2 znver3 znver4 bdver2 bdver3 bdver4 x86-64-v3 x86-64-v4)
  set(contracting "")
  foreach(token IN LISTS tokens)
    if(token MATCHES "^-ffast-math$|^-Ofast$|^-funsafe-math-optimizations$")
      message(FATAL_ERROR "Kappa: '${token}' changes float results; the exact accelerators need IEEE float "
                          "semantics (remove it from CMAKE_CXX_FLAGS)")
    elseif(token MATCHES "^-ffp-contract=(fast|on)$")
      set(contracting "${token}")
    elseif(token STREQUAL "-ffp-contract=off")
      set(contracting "")
    elseif(token STREQUAL "-mfma")
      set(contracting "${token}")
    elseif(token MATCHES "^-march=(.*)$")
      if(CMAKE_MATCH_1 IN_LIST fma_arches)
        set(contracting "${token}")
      endif()
    endif()
  endforeach()
  if(contracting)
    message(FATAL_ERROR "Kappa: '${contracting}' lets the compiler fuse a*b+c into FMA, which changes float results "
                        "and breaks the exact accelerators' bitwise agreement; add -ffp-contract=off after it")
  endif()
endfunction()
