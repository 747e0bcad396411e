#!/bin/bash
# docs/options.md is what the options table says (gen_flowscape --options-markdown): an option
# added, removed or changed in dataset_tools/release/src/options.cpp fails here until the page is
# written again with `build/apps/gen_flowscape --options-markdown > docs/options.md`.
set -u
bin=$1 docs=$2
if ! diff -u "$docs/options.md" <("$bin/gen_flowscape" --options-markdown); then
  echo "docs/options.md differs from the options table: run" \
    "'build/apps/gen_flowscape --options-markdown > docs/options.md'" >&2
  exit 1
fi
echo "docs/options.md is the options table's"
