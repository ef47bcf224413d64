# SPDX-License-Identifier: Apache-2.0
# Warnings are errors on every target.
set(MODCP_WARNINGS -Wall -Wextra -Wconversion -Wshadow -Wstrict-prototypes
    -Wmissing-prototypes -Wundef -Wcast-qual -Werror)
function(modcp_warnings target)
  target_compile_options(${target} PRIVATE ${MODCP_WARNINGS})
endfunction()
