#!/bin/sh
# The strip CPack runs on the installed programs and plugins (CMAKE_STRIP),
# as Debian's dh_strip does: also without the compiler's .comment and the
# .note sections (lintian: binary-has-unneeded-section).
exec strip --remove-section=.comment --remove-section=.note "$@"
