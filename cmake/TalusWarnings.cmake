# Compile options every Talus target gets: warnings (errors with TALUS_WERROR), sanitizers, code generation.
# Applied per target so third-party code (OpenFOAM, CGAL headers included as SYSTEM) is left alone.

## talus_target_defaults(<target>): warnings, sanitizers, OpenMP where enabled.
function(talus_target_defaults target)
  # Calls between functions of one Talus library go direct (and may be inlined) instead of
  # through the PLT: nothing interposes Talus's own symbols, and the contact loop calls the
  # geometry routine for every pair. Inline functions are hidden for the same reason (none has
  # a static local that two libraries would need to share).
  target_compile_options(${target} PRIVATE -fno-semantic-interposition -fvisibility-inlines-hidden)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                         -Wold-style-cast -Wcast-align -Wformat=2)
  if(TALUS_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(TALUS_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                           -fno-sanitize-recover=all)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()
