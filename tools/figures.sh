#!/usr/bin/env bash
# make figures: the seed's figures (spherical-billboards.txt figures 1, 2, 4, 5, 7, 8, 10) as
# pictures rendered by sbfx-play (headless, over its test scene), composed into panels with
# ImageMagick's montage, into docs/figures/ (described in docs/figures.md). Also the look of the
# explosion at t = 0.25, 1.0 and 1.5 s (docs/figures/look-explosion-t*.png).
# Usage: tools/figures.sh [BUILD] (default build). Scenes it needs are written to
# BUILD/figures/scenes/; frames to BUILD/figures/; timings to docs/figures/times.txt.
set -eu
cd "$(dirname "$0")/.."
BUILD=${1:-build}
PLAYER=$BUILD/sbfx-play
WORK=$BUILD/figures
OUT=docs/figures
PANEL=480x270
# Debian's ImageMagick 6 (tools/deps.sh test): montage, composite and convert from /usr/bin
# (a convert earlier in PATH may be another program).
IM=${IM_BIN:-/usr/bin}
for tool in montage composite convert compare; do
    [ -x "$IM/$tool" ] || { echo "figures: $IM/$tool missing (tools/deps.sh test installs imagemagick)" >&2; exit 1; }
done
mkdir -p "$WORK/scenes" "$OUT"

# play NAME ARGS...: sbfx-play --headless into $WORK/NAME; what it prints kept in $WORK/NAME.log.
play() {
    local name=$1
    shift
    rm -rf "${WORK:?}/$name"
    "$PLAYER" --headless --out "$WORK/$name" "$@" >"$WORK/$name.log" 2>&1 ||
        { cat "$WORK/$name.log" >&2; exit 1; }
}
frame() { printf '%s/%s/frame-%04d.png' "$WORK" "$1" "$2"; }

# compose OUT TILE FILE LABEL [FILE LABEL ...]: panels of $PANEL with a caption under each.
compose() {
    local out=$1 tile=$2 geometry=${GEOMETRY:-$PANEL}
    shift 2
    local args=()
    while [ $# -gt 0 ]; do args+=(-label "${2//%/%%}" "$1"); shift 2; done # montage reads % escapes
    "$IM/montage" "${args[@]}" -tile "$tile" -geometry "$geometry+3+3" -background '#1e1e1e' \
        -fill '#f0f0f0' -font DejaVu-Sans -pointsize 14 -depth 8 "$out.tmp.png"
    "$IM/convert" "$out.tmp.png" -strip -depth 8 -define png:compression-level=9 "$out"
    rm -f "$out.tmp.png"
    echo "figures: $out ($(stat -c %s "$out") bytes)"
}

# mean_ms NAME: sbfx's mean update+render+glFinish time of that run, as sbfx-play printed it.
mean_ms() { sed -n 's/.*update+render+glFinish: mean \([0-9.]*\) ms, max \([0-9.]*\) ms.*/\1/p' "$WORK/$1.log"; }
max_ms() { sed -n 's/.*update+render+glFinish: mean \([0-9.]*\) ms, max \([0-9.]*\) ms.*/\2/p' "$WORK/$1.log"; }

# ---- figure 1: billboards clipped by the ground and a box ------------------------------------
cat >"$WORK/scenes/fig-clip.cfg" <<'EOF'
# Figure 1: large still smoke particles resting on the ground and against a box.
render = { target_scale = 1; };
camera = { target = [0.2, 0.35, 1.4]; distance = 2.5; height = 0.6; azimuth = 10.0; orbit = 0.0; fov = 50.0; };
media = { smoke = { albedo = 0.7; density = 0.9; color = [0.85, 0.85, 0.88];
                    detail = { source = "procedural"; strength = 0.4; window = 0.15; }; }; };
effects = { bank = { steps = (
  { type = "emitter"; medium = "smoke"; count = 14; spawn_radius = 0.9; speed = [0.0, 0.02]; upward = 0.0;
    lifetime = [30.0, 30.0]; radius = [0.7, 0.7]; radius_jitter = 0.15; drag = 5.0; buoyancy = 0.0;
    intensity = [1.0, 1.0]; fade_in = 0.0; } ); }; };
triggers = { timeline = ( { effect = "bank"; time = 0.0; position = [0.6, 0.15, 0.3]; } ); };
EOF
for op in planar spherical; do
    play "clip-$op" --scene "$WORK/scenes/fig-clip.cfg" --size $PANEL --fps 2 --frames 3 --opacity "$op" --quiet
done
compose "$OUT/fig1-clipping.png" 2x1 \
    "$(frame clip-planar 2)" "planar: hard lines where they cut ground and box" \
    "$(frame clip-spherical 2)" "spherical: no clipping lines"

# ---- figure 2: popping at the near plane ------------------------------------------------------
cat >"$WORK/scenes/fig-near.cfg" <<'EOF'
# Figure 2: the camera circles inside a cluster of still smoke particles; its near plane sweeps
# through them.
render = { target_scale = 1; };
camera = { target = [0.0, 1.0, 0.0]; distance = 0.7; height = 1.0; azimuth = 0.0; orbit = 40.0; fov = 60.0; };
media = { smoke = { albedo = 0.7; density = 1.2; color = [0.85, 0.85, 0.88];
                    detail = { source = "procedural"; strength = 0.4; window = 0.15; }; }; };
effects = { cluster = { steps = (
  { type = "emitter"; medium = "smoke"; count = 50; spawn_radius = 1.2; speed = [0.0, 0.01]; upward = 0.0;
    lifetime = [30.0, 30.0]; radius = [0.5, 0.5]; radius_jitter = 0.2; drag = 5.0; buoyancy = 0.0;
    intensity = [1.0, 1.0]; fade_in = 0.0; } ); }; };
triggers = { timeline = ( { effect = "cluster"; time = 0.0; position = [0.0, 1.0, 0.0]; } ); };
EOF
NEAR_FRAMES=37
for op in planar spherical; do
    play "near-$op" --scene "$WORK/scenes/fig-near.cfg" --size $PANEL --fps 12 --frames $NEAR_FRAMES --opacity "$op" --quiet
done
# mae A B: ImageMagick's mean absolute difference of two pictures, in percent of full scale
mae() { "$IM/compare" -metric MAE "$1" "$2" null: 2>&1 | sed 's/.*(\([0-9.e+-]*\)).*/\1/' | awk '{ printf "%.2f", $1 * 100 }'; }
# The pair of adjacent frames where the planar picture changes most beyond what the spherical
# one does (the camera's own motion changes both alike): a particle crossed the near plane.
best=2 best_d=-1
for i in $(seq 1 $((NEAR_FRAMES - 2))); do
    d=$(awk -v a="$(mae "$(frame near-planar "$i")" "$(frame near-planar $((i + 1)))")" \
            -v b="$(mae "$(frame near-spherical "$i")" "$(frame near-spherical $((i + 1)))")" 'BEGIN { print a - b }')
    if awk -v a="$d" -v b="$best_d" 'BEGIN { exit !(a > b) }'; then best=$i best_d=$d; fi
done
next=$((best + 1))
for op in planar spherical; do
    "$IM/composite" -compose difference "$(frame near-$op $next)" "$(frame near-$op $best)" "$WORK/near-$op-diff.tmp.png"
    "$IM/convert" "$WORK/near-$op-diff.tmp.png" -colorspace gray -evaluate multiply 4 "$WORK/near-$op-diff.png"
done
planar_pct=$(mae "$(frame near-planar "$best")" "$(frame near-planar $next)")
spherical_pct=$(mae "$(frame near-spherical "$best")" "$(frame near-spherical $next)")
GEOMETRY=368x207 compose "$OUT/fig2-popping.png" 3x2 \
    "$(frame near-planar "$best")" "planar, frame $best" \
    "$(frame near-planar $next)" "planar, frame $next (1/12 s later)" \
    "$WORK/near-planar-diff.png" "planar: change x4 ($planar_pct % mean)" \
    "$(frame near-spherical "$best")" "spherical, frame $best" \
    "$(frame near-spherical $next)" "spherical, frame $next" \
    "$WORK/near-spherical-diff.png" "spherical: change x4 ($spherical_pct % mean)"

# ---- figure 4: a particle system, planar and spherical ----------------------------------------
for op in planar spherical; do
    play "system-$op" --scene scenes/explosion.cfg --size $PANEL --fps 2 --frames 4 --scale 1 --opacity "$op" --quiet
done
compose "$OUT/fig4-planar-vs-spherical.png" 2x1 \
    "$(frame system-planar 3)" "planar billboards (explosion, t = 1.5 s)" \
    "$(frame system-spherical 3)" "spherical billboards"

# ---- figure 5: high-albedo dust and low-albedo smoke ------------------------------------------
for medium in dust smoke; do
    if [ $medium = dust ]; then look='albedo = 0.9; density = 0.5; color = [0.9, 0.78, 0.6];'
    else look='albedo = 0.08; density = 0.5; color = [0.6, 0.6, 0.62];'; fi
    cat >"$WORK/scenes/fig-$medium.cfg" <<EOF
# Figure 5: the same plume in $medium.
render = { target_scale = 1; };
camera = { target = [-0.4, 1.3, -0.6]; distance = 4.5; height = 1.5; azimuth = -20.0; orbit = 0.0; fov = 50.0; };
lights = ( { type = "directional"; direction = [-0.5, -0.7, -0.3]; color = [1.6, 1.5, 1.35]; } );
media = { $medium = { $look detail = { source = "procedural"; strength = 0.6; window = 0.15; }; }; };
effects = { plume = { steps = (
  { type = "emitter"; medium = "$medium"; count = 40; spawn_radius = 0.5; speed = [0.3, 0.8]; upward = 0.9;
    lifetime = [4.0, 5.0]; radius = [0.5, 1.4]; radius_jitter = 0.2; drag = 0.6; buoyancy = 0.6;
    intensity = [1.0, 0.3]; fade_in = 0.15; } ); }; };
triggers = { timeline = ( { effect = "plume"; time = 0.0; position = [-0.4, 0.0, -0.6]; } ); };
EOF
    play "albedo-$medium" --scene "$WORK/scenes/fig-$medium.cfg" --size $PANEL --fps 2 --frames 7 --quiet
done
compose "$OUT/fig5-dust-vs-smoke.png" 2x1 \
    "$(frame albedo-dust 6)" "dust: albedo 0.9 (scatters the light)" \
    "$(frame albedo-smoke 6)" "smoke: albedo 0.08 (absorbs it)"

# ---- figure 7: particle targets 1, 1/2, 1/4, 1/8 with their times ------------------------------
: >"$OUT/times.txt"
for s in 1 2 4 8; do
    play "scale-$s" --scene scenes/explosion.cfg --size 960x540 --fps 12 --frames 13 --scale $s
    printf 'scale %s: sbfx update+render+glFinish mean %s ms, max %s ms per frame (explosion, 960x540, frames t = 0..1 s)\n' \
        "$s" "$(mean_ms scale-$s)" "$(max_ms scale-$s)" >>"$OUT/times.txt"
done
label_scale() { # S NAME
    local w=$((960 / $1)) h=$((540 / $1))
    printf '%s (%dx%d): %s ms per frame' "$2" "$w" "$h" "$(mean_ms "scale-$1")"
}
# the cloud at full resolution (a crop), so the targets' resolution shows
for s in 1 2 4 8; do "$IM/convert" "$(frame scale-$s 12)" -crop 440x248+240+120 +repage "$WORK/scale-$s.png"; done
GEOMETRY=440x248 compose "$OUT/fig7-target-scale.png" 2x2 \
    "$WORK/scale-1.png" "$(label_scale 1 'screen')" \
    "$WORK/scale-2.png" "$(label_scale 2 'half')" \
    "$WORK/scale-4.png" "$(label_scale 4 'quarter')" \
    "$WORK/scale-8.png" "$(label_scale 8 'one eighth')"

# ---- figure 8: heat shimmer --------------------------------------------------------------------
# the campfire seen from the front, the wall's straight edges and the ground's checker behind it;
# once as it is and once with the heat's strength 0
camera='camera = { target = [-0.3, 0.6, 0.0]; distance = 2.2; height = 0.45; azimuth = 90.0; orbit = 0.0; fov = 50.0; };'
sed "s|^camera = .*|$camera|" scenes/campfire.cfg >"$WORK/scenes/fig-heat.cfg"
sed 's/strength = 0.012;/strength = 0.0;/' "$WORK/scenes/fig-heat.cfg" >"$WORK/scenes/fig-noheat.cfg"
grep -q 'strength = 0.0;' "$WORK/scenes/fig-noheat.cfg" || { echo "figures: campfire's heat strength not found" >&2; exit 1; }
play heat-on --scene "$WORK/scenes/fig-heat.cfg" --size 960x540 --fps 4 --frames 7 --quiet
play heat-off --scene "$WORK/scenes/fig-noheat.cfg" --size 960x540 --fps 4 --frames 7 --quiet
crop=480x270+400+100 # around the fire, at full resolution: the shimmer is a few pixels
"$IM/convert" "$(frame heat-off 6)" -crop $crop +repage "$WORK/heat-off.png"
"$IM/convert" "$(frame heat-on 6)" -crop $crop +repage "$WORK/heat-on.png"
"$IM/composite" -compose difference "$WORK/heat-on.png" "$WORK/heat-off.png" "$WORK/heat-diff.tmp.png"
"$IM/convert" "$WORK/heat-diff.tmp.png" -colorspace gray -evaluate multiply 8 "$WORK/heat-diff.png"
compose "$OUT/fig8-heat-shimmer.png" 3x1 \
    "$WORK/heat-off.png" "campfire without heat" \
    "$WORK/heat-on.png" "with heat shimmer" \
    "$WORK/heat-diff.png" "difference x8: where the heat displaces"

# ---- figure 10: the animation --------------------------------------------------------------------
play anim --scene scenes/explosion.cfg --size 960x540 --fps 4 --frames 9 --quiet
args=()
for i in 1 2 3 4 5 6 7 8; do
    args+=("$(frame anim $i)" "t = $(awk -v i=$i 'BEGIN { printf "%.2f", i / 4 }') s")
done
GEOMETRY=320x180 compose "$OUT/fig10-animation.png" 4x2 "${args[@]}"

# ---- issue 27: fire lights the host at night, smoke shades it by day ------------------------------
# night.cfg at the flash and after, with and without render.host_lights; dust-storm.cfg (a sun 30
# degrees high) at 2 s with and without render.host_shadows. The same run otherwise.
sed 's/host_lights   = true;/host_lights   = false;/' scenes/night.cfg >"$WORK/scenes/night-unlit.cfg"
sed 's/host_shadows = true;/host_shadows = false;/' scenes/dust-storm.cfg >"$WORK/scenes/dust-storm-unshaded.cfg"
play night --scene scenes/night.cfg --size 960x540 --fps 5 --frames 7 --quiet
play night-unlit --scene "$WORK/scenes/night-unlit.cfg" --size 960x540 --fps 5 --frames 7 --quiet
GEOMETRY=480x270 compose "$OUT/night-host-lights.png" 2x2 \
    "$(frame night 3)" "night.cfg, t = 0.6 s: host_lights" "$(frame night-unlit 3)" "t = 0.6 s: without" \
    "$(frame night 6)" "t = 1.2 s: host_lights" "$(frame night-unlit 6)" "t = 1.2 s: without"
play shadow --scene scenes/dust-storm.cfg --size 960x540 --fps 1 --frames 3 --quiet
play shadow-off --scene "$WORK/scenes/dust-storm-unshaded.cfg" --size 960x540 --fps 1 --frames 3 --quiet
GEOMETRY=480x270 compose "$OUT/shadow-dust-storm.png" 2x1 \
    "$(frame shadow 2)" "dust-storm.cfg, t = 2 s: host_shadows" "$(frame shadow-off 2)" "without"

# ---- the explosion's look now (compare docs/figures/before-*.png) -------------------------------
play look --scene scenes/explosion.cfg --size 960x540 --fps 4 --frames 7 --quiet
for pair in 1:0.25 4:1.0 6:1.5; do
    "$IM/convert" "$(frame look "${pair%%:*}")" -strip "$OUT/look-explosion-t${pair#*:}.png"
done
echo "figures: $OUT/look-explosion-t{0.25,1.0,1.5}.png, $OUT/times.txt"
