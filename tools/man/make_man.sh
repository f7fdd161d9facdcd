#!/usr/bin/env bash
# Builds a tool's man page with help2man (Debian's help2man) from its --help and --version.
# For `plateball` every subcommand's --help becomes a section of the page, so the page stays the
# help the tool prints.
#   make_man.sh TOOL_BINARY NAME OUTPUT.1 "ONE LINE DESCRIPTION"
set -euo pipefail
tool=$1 name=$2 out=$3 description=$4
include=$(mktemp)
trap 'rm -f "$include"' EXIT
{
  echo "[SEE ALSO]"
  echo "The README and docs/ of the plateball sources (problem files, output contract);"
  echo "units in docs/units.md; bash completion is installed with the tools."
} > "$include"
# Subcommands: the names under "Subcommands:" in the tool's help.
subcommands=$("$tool" --help | awk '/^Subcommands:/{s=1; next} s && /^  [a-z]/{print $1}')
# A subcommand group (`rig export|replay`) adds a section per member.
escape() { sed -e 's/\\/\\\\/g' -e 's/^\./\\\&./' -e 's/^/ /'; }
for sub in $subcommands; do
  {
    echo "[SUBCOMMAND: $sub]"
    "$tool" "$sub" --help | escape
  } >> "$include"
  for member in $("$tool" "$sub" --help | awk '/^Subcommands:/{s=1; next} s && /^  [a-z]/{print $1}'); do
    {
      echo "[SUBCOMMAND: $sub $member]"
      "$tool" "$sub" "$member" --help | escape
    } >> "$include"
  done
done
help2man --no-info --no-discard-stderr --name="$description" --include="$include" \
  --version-string="$("$tool" --version | awk '{print $NF}')" -o "$out" "$tool"
# help2man shows the program as it was called: the page names the installed command.
sed -i -e "s|$(dirname "$tool")/||g" "$out"
[[ "$(basename "$tool")" == "$name" ]] || sed -i -e "s|$(basename "$tool")|$name|g" "$out"
