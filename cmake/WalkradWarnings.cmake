# walkrad_warnings(target): the warning set every walkrad target builds with.
function(walkrad_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wno-unused-parameter)
endfunction()
