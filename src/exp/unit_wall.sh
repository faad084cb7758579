# unit_wall.sh: the one reader of the wall time a unit recorded, sourced by
# study_cost.sh (the study's cost) and verify_deep.sh (its projected time),
# so the two never count a unit differently.
#
# unit_walls ROOT < paths   one unit per line, its table's path under ROOT
#   (a results root: frozen, build/smoke, ...); prints per unit
#     path <TAB> unit_s <TAB> eval_s <TAB> how
#   unit_s  what running the unit cost, from its tables' `# wall_s:` lines:
#     how=recorded  the table's own wall time;
#     how=trained   the unit trains (its manifest recipe runs main-run) but
#                   the table there is a re-evaluation of its weights: the
#                   training run's wall time, which the re-evaluation carries
#                   as `# trained_wall_s:` (training and its own evaluation);
#     how=folder    a unit that writes a folder of tables (.../unit.tsv, the
#                   sensitivity units): one wall time per invocation (the
#                   tables one command wrote at one date share it: the
#                   largest), summed over the invocations;
#     how=none      no table or no wall time (unit_s and eval_s empty).
#   eval_s  the evaluation part of a model unit: a re-evaluation's own wall
#     time, or wall_s less the `# train_time: train_s` a training run
#     records; empty where the table says neither.
# Recorded times are those of the machines and loads the units ran on.
unit_wall_trains_re() {
    # the targets of the manifest's units that train, as one regex on paths
    bash "$(dirname "${BASH_SOURCE[0]}")/../base/manifest.sh" rows |
        awk -F'\t' '$1 == "UNIT" && $5 ~ /main-run / {
            t = $2 "/" $3; gsub(/\./, "\\.", t); gsub(/%/, "[0-9]+", t); r = r (r == "" ? "" : "|") "^" t "$" }
            END { print r == "" ? "^$" : "(" r ")" }'
}

unit_walls() {
    local root=$1 trains paths
    trains=$(unit_wall_trains_re)
    paths=$(cat)
    [ -n "$paths" ] || return 0
    # the tables to read: each unit's own, and every table of a folder unit
    {
        while IFS= read -r p; do
            case $p in
                */unit.tsv) [ -d "$root/$(dirname "$p")" ] && find "$root/$(dirname "$p")" -name '*.tsv' ! -name '*.tmp*' ! -name '.*' ;;
                *) [ -f "$root/$p" ] && printf '%s\n' "$root/$p" ;;
            esac
        done <<<"$paths"
    } | sort -u | { mapfile -t files; [ ${#files[@]} -gt 0 ] || files=(/dev/null)
        awk -v root="$root/" -v trains="$trains" -v paths="$paths" '
        FNR == 1 { f = substr(FILENAME, length(root) + 1); seen[f] = 1 }
        !/^#/ { nextfile }
        /^# wall_s: / { W[f] = $3 }
        /^# trained_wall_s: / { TW[f] = $3 }
        /^# train_time: train_s / { TR[f] = $4 }
        /^# command: / { C[f] = substr($0, 12) }
        /^# date: / { D[f] = $3 }
        END {
            n = split(paths, P, "\n")
            for (i = 1; i <= n; i++) {
                p = P[i]; if (p == "") continue
                u = ""; e = ""; how = "none"
                if (p ~ /\/unit\.tsv$/) {
                    d = p; sub(/unit\.tsv$/, "", d); split("", inv); any = 0
                    for (g in W) if (index(g, d) == 1) { k = C[g] SUBSEP D[g]; if (!(k in inv) || W[g] + 0 > inv[k] + 0) inv[k] = W[g]; any = 1 }
                    if (any) { u = 0; for (k in inv) u += inv[k]; how = "folder" }
                } else if (p in seen) {
                    if (p ~ trains && (p in TW)) { u = TW[p]; how = "trained" }
                    else if (p in W) { u = W[p]; how = "recorded" }
                    if (p in TW && p in W) e = W[p]
                    else if (p in TR && p in W && W[p] - TR[p] > 0) e = W[p] - TR[p]
                }
                printf "%s\t%s\t%s\t%s\n", p, u, e, how
            }
        }' "${files[@]}"; }
}
