#!/usr/bin/env bash
# Formats the C++ sources with clang-format (.clang-format at the top).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
git ls-files '*.hpp' '*.cpp' '*.cu' '*.cuh' | xargs clang-format -i
