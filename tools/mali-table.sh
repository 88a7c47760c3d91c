#!/bin/sh
# Markdown tables of tools/shader-stats.sh's CSV (docs/gpus.md): for each GPU, every distinct
# fragment shader variant the example scenes compile, costliest first, with the scenes that
# use it. Usage: tools/mali-table.sh MALI.csv [GPU ...]   (default: g52 g610)
set -eu
[ $# -ge 1 ] || { echo "usage: $0 MALI.csv [GPU ...]" >&2; exit 2; }
csv=$1
shift
[ $# -gt 0 ] || set -- g52 g610
for gpu in "$@"; do
    echo
    echo "| $gpu: fragment shader | variant | scenes | instructions | cycles | arith | texture | varying | load/store | registers | threads | spills |"
    echo "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    awk -F, -v gpu="$gpu" '$1 == gpu && $6 == "fragment" {
        k = $4 FS $5
        if (!(k in row)) {
            row[k] = sprintf("| %s | %s | %%s | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %s | %s | %d |", $4,
                             $5 == "-" ? "" : $5, $7, $8, $9, $10, $11, $12, $13, $14, $15)
            cyc[k] = $8
        }
        if (!((k, $3) in seen)) {
            list = (k in scenes) ? scenes[k] " " $3 : $3
            scenes[k] = list
        }
        seen[k, $3] = 1
    }
    END { for (k in row) printf "%09.4f\t" row[k] "\n", cyc[k], scenes[k] }' "$csv" | sort -r | cut -f2-
done
