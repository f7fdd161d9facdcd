# bash completion for `plateball` and `isoparallel_solve` (installed to
# share/bash-completion/completions). Subcommands and options are read from the tools' own
# --help, so the completion always matches the installed tool.

_plateball_words() {  # the options (and, for the top level, subcommands) of "$@" --help
  "$@" --help 2>/dev/null | awk '
    /^Subcommands:/ { s = 1; next }
    s && /^  [a-z]/ { print $1; next }
    { for (i = 1; i <= NF; ++i) if ($i ~ /^-/) { n = split($i, a, ","); for (k = 1; k <= n; ++k) if (a[k] ~ /^-/) print a[k] } }' |
    sed -e 's/[^A-Za-z0-9_-].*$//' | sort -u
}

_plateball() {
  local cur prev tool sub i
  cur=${COMP_WORDS[COMP_CWORD]}
  prev=${COMP_WORDS[COMP_CWORD - 1]}
  tool=${COMP_WORDS[0]}
  case $prev in
    --out | --svg | --csv | --samples-file | --mjcf) COMPREPLY=($(compgen -f -- "$cur")); return ;;
  esac
  sub=
  if [[ $(basename "$tool") == plateball ]]; then
    for ((i = 1; i < COMP_CWORD; ++i)); do
      [[ ${COMP_WORDS[i]} != -* ]] && { sub=${COMP_WORDS[i]}; break; }
    done
    if [[ -z $sub ]]; then
      COMPREPLY=($(compgen -W "$(_plateball_words "$tool")" -- "$cur"))
      return
    fi
    # A subcommand group (`rig export|replay`): its subcommands first, then the chosen one's options.
    local group sub2=
    group=$("$tool" "$sub" --help 2>/dev/null | awk '/^Subcommands:/ { s = 1; next } s && /^  [a-z]/ { print $1 }')
    if [[ -n $group ]]; then
      for ((i = i + 1; i < COMP_CWORD; ++i)); do
        [[ ${COMP_WORDS[i]} != -* ]] && { sub2=${COMP_WORDS[i]}; break; }
      done
      if [[ -z $sub2 ]]; then
        COMPREPLY=($(compgen -W "$group" -- "$cur"))
        return
      fi
      sub="$sub $sub2"
    fi
  fi
  if [[ $cur == -* ]]; then
    COMPREPLY=($(compgen -W "$(_plateball_words "$tool" $sub)" -- "$cur"))
  else
    COMPREPLY=($(compgen -f -X '!*.json' -- "$cur") $(compgen -d -- "$cur"))
  fi
}

complete -F _plateball plateball isoparallel_solve
