#!/usr/bin/env bash
# What `make paper` needs from TeX: pdflatex and every package paper/main.tex
# loads with \usepackage, each looked up with kpsewhich. As root the missing
# ones are installed from Debian (the package that ships each .sty, below);
# otherwise, or if the install leaves one missing, each missing .sty is named
# with its Debian package and the exact command, and the status is 1.
# PAPER_DEPS_NOINSTALL=1 reports without installing and PDFLATEX names the
# program looked for (tests).
set -u
tex=${1:-paper/main.tex}
pdflatex=${PDFLATEX:-pdflatex}

# the Debian package that ships each .sty the write-up loads (texlive 2022)
deb_of() {
  case "$1" in
    booktabs|xcolor|pdflscape) echo texlive-latex-recommended ;;
    geometry|graphicx|longtable|amsmath|ifthen|hyperref) echo texlive-latex-base ;;
    *) echo texlive-latex-extra ;;
  esac
}

# the packages of every \usepackage[..]{a,b} line, one per line
stys=$(sed -n 's/^[^%]*\\usepackage\(\[[^]]*\]\)\{0,1\}{\([^}]*\)}.*/\2/p' "$tex" | tr ',' '\n' | tr -d ' ' | sort -u)
[ -n "$stys" ] || { echo "paper-deps: $tex loads no package (cannot read it?)" >&2; exit 1; }

missing() {
  command -v "$pdflatex" >/dev/null || echo "$pdflatex:texlive-latex-base"
  for s in $stys; do
    if ! command -v kpsewhich >/dev/null || [ -z "$(kpsewhich "$s.sty" 2>/dev/null)" ]; then
      echo "$s.sty:$(deb_of "$s")"
    fi
  done
}

m=$(missing)
[ -z "$m" ] && exit 0
debs=$(printf '%s\n' $m | cut -d: -f2 | sort -u | tr '\n' ' ')
if [ "$(id -u)" = 0 ] && [ "${PAPER_DEPS_NOINSTALL:-0}" != 1 ]; then
  echo "paper-deps: installing $debs(for $(printf '%s\n' $m | cut -d: -f1 | tr '\n' ' '))" >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q >/dev/null && apt-get install -y -q --no-install-recommends $debs >/dev/null
  m=$(missing)
  [ -z "$m" ] && exit 0
  debs=$(printf '%s\n' $m | cut -d: -f2 | sort -u | tr '\n' ' ')
fi
for x in $m; do echo "paper-deps: missing ${x%%:*} (Debian package ${x#*:})" >&2; done
echo "paper-deps: run: sudo apt-get update && sudo apt-get install -y $debs" >&2
exit 1
