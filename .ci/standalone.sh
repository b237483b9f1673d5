#!/usr/bin/env bash
# The repository stands alone: nothing in it may point outside it. Fails, listing every hit,
# on a path into a sibling checkout (`../shared`), an absolute path into the machine it was
# written on (`/work/shared`), or a citation of the documents that lived there (`DESIGN §n`,
# `DESIGN.md`, `ROBOTS.md`): cite docs/design.md, the thesis, a paper or a robot's own
# description instead.
set -euo pipefail
cd "$(dirname "$0")/.."
patterns=(-e '\.\./shared' -e 'DESIGN §' -e 'DESIGN\.md' -e 'ROBOTS\.md' -e '/work/shared')
if hits=$(git grep -n -I -E "${patterns[@]}" -- . ':(exclude).ci/standalone.sh'); then
  echo "references outside the repository (cite docs/design.md, the thesis or a paper):" >&2
  echo "$hits" >&2
  exit 1
fi
echo "standalone: no reference outside the repository"
