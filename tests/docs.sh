#!/usr/bin/env bash
# The documentation's checks (issue 19), in `make test`:
#   docs/links/FILE    every relative link and image of FILE (README.md, docs/**/*.md) names a
#                      file or folder that exists; a #anchor names a heading of the Markdown
#                      file it points to (GitHub's anchors: lower case, punctuation dropped,
#                      spaces to hyphens, -1, -2... for repeats). Links in code are not links.
#   docs/example/FILE:LINE
#                      a fenced code block right after a line `<!-- example: PATH -->` is exactly
#                      the file PATH (relative to the repository root); after
#                      `<!-- example: PATH:A-B -->` exactly its lines A to B (1-based,
#                      inclusive). PATH must be built by the tests: named (it or its folder) in
#                      the Makefile, .ci/ or a test script.
#   docs/make-help     `make help` lists every .PHONY target a user runs.
#   docs/requirements  README's Requirements name the packages make test-fresh's bare root has.
# Usage: tests/docs.sh. Prints "ok - docs/..." / "not ok - docs/...: why"; exits 1 on a failure.
set -u
cd "$(dirname "$0")/.." || exit 1

failures=0
ok() { echo "ok - docs/$1"; }
not_ok() {
    echo "not ok - docs/$1: $2"
    failures=$((failures + 1))
}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# md_scan FILE: one line per link ("L<TAB>line<TAB>target"), per example marker
# ("E<TAB>line<TAB>spec<TAB>first<TAB>last", the block's content lines; first > last: empty;
# first = 0: no block follows) and per heading ("H<TAB>line<TAB>anchor"), outside fenced code.
md_scan() {
    awk -v OFS='\t' '
    function slug(s) {
        s = tolower(s)
        gsub(/[^a-z0-9 _-]/, "", s)
        gsub(/ /, "-", s)
        return s
    }
    function fence_of(l) {
        if (match(l, /^ ? ? ?(```+|~~~+)/)) { f = substr(l, RSTART, RLENGTH); sub(/^ +/, "", f); return f }
        return ""
    }
    {
        line = $0
        f = fence_of(line)
        if (infence) {
            if (f != "" && substr(f, 1, 1) == substr(fencechar, 1, 1) && length(f) >= length(fencechar) && line ~ /^ ? ? ?(```+|~~~+)[ \t]*$/) {
                infence = 0
                if (pending) { print "E", markline, spec, first, NR - 1; pending = 0 }
            }
            next
        }
        if (f != "") {
            infence = 1; fencechar = f
            if (pending && NR == markline + 1) first = NR + 1
            else if (pending) { print "E", markline, spec, 0, 0; pending = 0 }
            next
        }
        if (pending) { print "E", markline, spec, 0, 0; pending = 0 }
        if (match(line, /^<!-- example: [^ ]+ -->[ \t]*$/)) {
            spec = line; sub(/^<!-- example: /, "", spec); sub(/ -->[ \t]*$/, "", spec)
            pending = 1; markline = NR
            next
        }
        if (line ~ /^#+ /) {
            h = line; sub(/^#+ +/, "", h); sub(/ +#* *$/, "", h)
            gsub(/`/, "", h)
            s = slug(h)
            n = seen[s]++
            print "H", NR, (n ? s "-" n : s)
        }
        gsub(/`[^`]*`/, "", line)        # inline code is not a link
        rest = line
        while (match(rest, /\]\([^)]*\)/)) {
            t = substr(rest, RSTART + 2, RLENGTH - 3)
            sub(/[ \t]+".*$/, "", t)       # [x](path "title")
            print "L", NR, t
            rest = substr(rest, RSTART + RLENGTH)
        }
        if (match(line, /^ ? ? ?\[[^]]+\]:[ \t]+[^ \t]+/)) {
            t = line; sub(/^ *\[[^]]+\]:[ \t]+/, "", t); sub(/[ \t].*$/, "", t)
            print "L", NR, t
        }
        rest = line
        while (match(rest, /(src|href)="[^"]*"/)) {
            t = substr(rest, RSTART, RLENGTH); sub(/^[a-z]+="/, "", t); sub(/"$/, "", t)
            print "L", NR, t
            rest = substr(rest, RSTART + RLENGTH)
        }
    }
    END { if (pending) print "E", markline, spec, 0, 0 }' "$1"
}

# built_by_tests PATH: the file or its folder is named where the tests are built and run.
built_by_tests() {
    local path=$1 dir
    dir=$(dirname "$path")
    grep -rqsF -- "$path" Makefile .ci tests --exclude=docs.sh && return 0
    grep -rqsF -- "$dir/" Makefile .ci tests --exclude=docs.sh
}

check_links() {
    local md=$1 scan=$2 dir problems="" count=0 kind line target path anchor resolved
    dir=$(dirname "$md")
    while IFS=$'\t' read -r kind line target; do
        [ "$kind" = L ] || continue
        case "$target" in
            "" | *://* | mailto:* | data:*) continue ;;
        esac
        count=$((count + 1))
        path=${target%%#*}
        anchor=""
        [ "$path" != "$target" ] && anchor=${target#*#}
        if [ -z "$path" ]; then
            resolved=$md
        else
            resolved=$dir/$path
            if [ ! -e "$resolved" ]; then
                problems="$problems; line $line: '$target' does not exist"
                continue
            fi
        fi
        if [ -n "$anchor" ]; then
            case "$resolved" in
                *.md)
                    if ! md_scan "$resolved" | awk -F'\t' -v a="$anchor" '$1 == "H" && $3 == a { f = 1 } END { exit !f }'; then
                        problems="$problems; line $line: '$target': no heading with the anchor #$anchor"
                    fi
                    ;;
            esac
        fi
    done <"$scan"
    if [ -z "$problems" ]; then
        ok "links/$md ($count links)"
    else
        not_ok "links/$md" "${problems#; }"
    fi
}

check_examples() {
    local md=$1 scan=$2 kind line spec first last path range a b name
    while IFS=$'\t' read -r kind line spec first last; do
        [ "$kind" = E ] || continue
        name="example/$md:$line"
        path=$spec
        range=""
        if [[ "$spec" =~ ^(.+):([0-9]+)-([0-9]+)$ ]]; then
            path=${BASH_REMATCH[1]}
            a=${BASH_REMATCH[2]}
            b=${BASH_REMATCH[3]}
            range="$a-$b"
        fi
        if [ "$first" -eq 0 ]; then
            not_ok "$name" "'<!-- example: $spec -->' is not followed by a fenced code block"
            continue
        fi
        if [ ! -f "$path" ]; then
            not_ok "$name" "$path does not exist"
            continue
        fi
        if [ -n "$range" ]; then
            if [ "$a" -lt 1 ] || [ "$b" -lt "$a" ] || [ "$b" -gt "$(wc -l <"$path")" ]; then
                not_ok "$name" "lines $range are not within $path ($(wc -l <"$path") lines)"
                continue
            fi
            sed -n "${a},${b}p" "$path" >"$tmp/want"
        else
            cat "$path" >"$tmp/want"
        fi
        if [ "$first" -le "$last" ]; then sed -n "${first},${last}p" "$md" >"$tmp/got"; else : >"$tmp/got"; fi
        if ! cmp -s "$tmp/want" "$tmp/got"; then
            local where
            where=$(diff "$tmp/want" "$tmp/got" | head -n 1)
            not_ok "$name" "the block (lines $first-$last) differs from $spec (diff: $where)"
        elif ! built_by_tests "$path"; then
            not_ok "$name" "$path is not built by the tests (named in no test script, .ci/ or the Makefile)"
        else
            ok "$name ($spec)"
        fi
    done <"$scan"
}

# make help prints the Makefile's "#   make TARGET" comment lines: every target a user runs
# (the .PHONY ones but the steps others call) must be among them.
check_make_help() {
    local help missing="" t
    help=$(make --no-print-directory help 2>&1)
    for t in $(sed -n 's/^\.PHONY://p' Makefile); do
        case "$t" in deps | lib | test-unit | test-gl | test-asan | test-platform | test-build | test-build-normal | test-build-asan | install-kiosk | uninstall-kiosk | FORCE) continue ;; esac
        printf '%s\n' "$help" | grep -q "^make \(\[\)\?$t\b" || missing="$missing $t"
    done
    if [ -z "$missing" ]; then
        ok "make-help ($(printf '%s\n' "$help" | wc -l) lines)"
    else
        not_ok make-help "make help does not list:$missing (a '#   make TARGET  what' line at the Makefile's top)"
    fi
}
check_make_help

# README's Requirements name what tests/fresh/run.sh (make test-fresh) puts in the bare root
# before the quick start: the `apt-get install ...` line there is its REQUIREMENTS, word for word.
check_requirements() {
    local want said
    want=$(sed -n 's/^REQUIREMENTS="\(.*\)"$/\1/p' tests/fresh/run.sh)
    said=$(sed -n '/^## Requirements/,/^## /p' README.md | grep -o '`apt-get install [^`]*`' | head -n 1 | tr -d '`')
    if [ -n "$want" ] && [ "$said" = "apt-get install $want" ]; then
        ok "requirements (README: '$said'; make test-fresh's bare root has the same)"
    else
        not_ok requirements "README's Requirements say '$said', tests/fresh/run.sh installs '$want'"
    fi
}
check_requirements

files=$( { echo README.md; find docs -name '*.md' 2>/dev/null | sort; } )
for md in $files; do
    [ -f "$md" ] || continue
    md_scan "$md" >"$tmp/scan"
    check_links "$md" "$tmp/scan"
    check_examples "$md" "$tmp/scan"
done
[ "$failures" -eq 0 ]
