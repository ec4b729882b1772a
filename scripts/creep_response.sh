#!/usr/bin/env bash
# The creep forces' frequency response (docs/src/theory/creep-response.md)
# on the paper's scene (N = 100 kN, F_x = 20 kN, 100 km/h, the concave
# reading), and what it costs against a passage:
#   - tables (CSV, H against w a0 / V) for the exact model on the growth
#     studies' fixed grid (configs/growth_exact.toml) and on the adapted
#     mesh (20 x 20, 0.2 mm steps), the simplified-transient model and
#     FASTSIM (40 x 40), at F_x = 20 kN and at F_x = 0 (the linear
#     theory's full adhesion), to out/creep_response/*.csv;
#   - the figure docs/src/figures/creep_response.png;
#   - the cost: REPEATS (default 5) runs each of one table (the torsional
#     loop's inputs xi_x and N, and all four) and of a 3-passage growth
#     study (growth_exact.toml; growth_discrete.toml), median CPU seconds,
#     to out/creep_response/cost.md;
#   - with CONVERGENCE=1, the table's convergence in level, lead, run-in,
#     period (interpolation), grid and step, to
#     out/creep_response/convergence.md (about 15 minutes more: the adapted
#     mesh's 30 x 30 and 0.1 mm runs).
# About 5 minutes on 2 cores (the adapted mesh's tables take most of it).
#   REPEATS=1 bash scripts/creep_response.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo build --release --quiet --bin corrugation --example creep_response
out=out/creep_response
mkdir -p "$out"
table=./target/release/examples/creep_response
adapted=(set=contact.grid=adapted set=passage.step_length=2e-4 set=contact.elements_x=20 set=contact.elements_y=20)
fine=(set=contact.grid=adapted set=passage.step_length=2e-4 set=contact.elements_x=40 set=contact.elements_y=40)
for f in 2e4 0; do
  $table configs/growth_exact.toml "$out/exact_fixed_f$f.csv" longitudinal_force=$f 2> "$out/exact_fixed_f$f.log"
  $table configs/growth_exact.toml "$out/exact_adapted_f$f.csv" longitudinal_force=$f "${adapted[@]}" \
    2> "$out/exact_adapted_f$f.log"
  $table configs/growth_exact.toml "$out/simplified_f$f.csv" longitudinal_force=$f "${fine[@]}" \
    set=contact.model=simplified-transient 2> "$out/simplified_f$f.log"
  $table configs/growth_exact.toml "$out/fastsim_f$f.csv" longitudinal_force=$f "${fine[@]}" \
    set=contact.model=fastsim set=contact.fastsim_bound=elliptic 2> "$out/fastsim_f$f.log"
done

if [ "${CONVERGENCE:-0}" = 1 ]; then
  c=configs/growth_exact.toml
  run() { local name=$1; shift; $table "$c" "$out/conv_$name.csv" "$@" 2> "$out/conv_$name.log"; }
  run base
  run level_half level=1.5e-3 level_n=2.5e-2
  run level_double level=6e-3 level_n=1e-1
  run lead2 lead=2
  run lead8 lead=8
  run run_in4 run_in=4
  run period16 period=16
  run grid02 set=contact.dx=2e-4 set=contact.dy=5e-4
  run adapted20 "${adapted[@]}" set=contact.solver=gauss-seidel
  run adapted20_step01 "${adapted[@]}" set=contact.solver=gauss-seidel set=passage.step_length=1e-4
  run adapted30 "${adapted[@]}" set=contact.solver=gauss-seidel set=contact.elements_x=30 set=contact.elements_y=30
  .venv/bin/python - "$out" > "$out/convergence.md" <<'EOF'
import sys, csv
import numpy as np
out = sys.argv[1]
keys = ["fx_creepage_x", "fy_creepage_y", "fy_spin", "fx_normal_force"]
def load(name):
    rows = [r for r in csv.reader(l for l in open(f"{out}/conv_{name}.csv") if not l.startswith("#"))]
    col = {k: i for i, k in enumerate(rows[0])}
    d = np.array([[float(v) for v in r] for r in rows[1:]])
    return d[:, 0], {k: d[:, col[k + "_re"]] + 1j * d[:, col[k + "_im"]] for k in keys}
def same_points(a, b):
    (wa, ha), (wb, hb) = load(a), load(b)
    out = []
    for k in keys:
        worst = 0.0
        for i, w in enumerate(wa):
            j = np.argmin(abs(wb - w))
            if abs(wb[j] - w) < 1e-6:
                worst = max(worst, abs(ha[k][i] - hb[k][j]) / abs(ha[k][0]))
        out.append(worst)
    return out
def hermite(w, h, x, inverse):
    f = 1 / h if inverse else h
    d, m = w[1] - w[0], len(w) - 1
    p = lambda k: np.conj(f[-k]) if k < 0 else f[k]
    s = lambda k: p(k) - p(k - 1) if k == m else 0.5 * (p(k + 1) - p(k - 1))
    i = min(int(x / d), m - 1)
    t = (x - w[i]) / d
    y = (2*t**3 - 3*t**2 + 1) * p(i) + (t**3 - 2*t**2 + t) * s(i) + (-2*t**3 + 3*t**2) * p(i + 1) + (t**3 - t**2) * s(i + 1)
    return 1 / y if inverse else y
def interpolation(coarse, fine, inverse):
    (wc, hc), (wf, hf) = load(coarse), load(fine)
    return [max(abs(hermite(wc, hc[k], x, inverse) - hf[k][i]) / abs(hf[k][0]) for i, x in enumerate(wf) if x < wc[-1])
            for k in keys]
rows = [
    ("level halved (3e-3 -> 1.5e-3; N 5e-2 -> 2.5e-2)", same_points("base", "level_half")),
    ("level doubled (6e-3; N 1e-1)", same_points("base", "level_double")),
    ("lead 4 -> 8 patch lengths", same_points("base", "lead8")),
    ("lead 2 -> 8 patch lengths", same_points("lead2", "lead8")),
    ("run-in 2 -> 4 patch lengths", same_points("base", "run_in4")),
    ("interpolation (1 / H), period 4 against 16 patch lengths", interpolation("base", "period16", True)),
    ("interpolation of H instead, period 4 against 16", interpolation("base", "period16", False)),
    ("fixed grid 0.4 x 1 -> 0.2 x 0.5 mm", same_points("base", "grid02")),
    ("adapted mesh 20 x 20: step 0.2 -> 0.1 mm", same_points("adapted20", "adapted20_step01")),
    ("adapted mesh 20 x 20 -> 30 x 30 (step 0.2 mm)", same_points("adapted20", "adapted30")),
    ("fixed grid 0.4 x 1 mm against adapted mesh 30 x 30", same_points("base", "adapted30")),
]
print("| what changes | xi_x -> F_x | xi_y -> F_y | spin -> F_y | N -> F_x |")
print("|---|---|---|---|---|")
for name, v in rows:
    print(f"| {name} | " + " | ".join(f"{x:.1e}" for x in v) + " |")
EOF
  cat "$out/convergence.md"
fi

# Cost: median CPU seconds of REPEATS runs.
repeats=${REPEATS:-5}
cpu_of_table() { # CONFIG INPUTS -> CPU seconds of the measurement
  $table "$1" "$out/cost.csv" inputs="$2" 2>&1 | sed -n 's/.*cpu \([0-9.]*\) s.*/\1/p'
}
cpu_of_passage() { # CONFIG -> CPU seconds per passage (median of passages 2 and 3)
  ./target/release/corrugation run --overwrite "$1" --set growth.passes=3 --set "growth.contact_history=[0]" \
    -o "$out/cost.h5" > /dev/null 2>&1
  .venv/bin/python -c "
import h5py, numpy as np
with h5py.File('$out/cost.h5') as f:
    print(float(np.median(f['passes/cpu_seconds'][1:])))"
}
median() { python3 -c "import sys, statistics; print(statistics.median(float(v) for v in sys.argv[1:]))" "$@"; }
{
  echo "| config | passes | passage (s CPU) | table xi_x, N (s CPU) | table, all four (s CPU) | xi_x, N per passage of the study | all four per passage |"
  echo "|---|---|---|---|---|---|---|"
  for config in growth_exact growth_discrete; do
    c=configs/$config.toml
    passes=$(sed -n 's/^passes *= *\([0-9]*\).*/\1/p' "$c")
    p=(); t2=(); t4=()
    for _ in $(seq "$repeats"); do
      p+=("$(cpu_of_passage "$c")")
      t2+=("$(cpu_of_table "$c" xn)")
      t4+=("$(cpu_of_table "$c" xysn)")
    done
    mp=$(median "${p[@]}"); m2=$(median "${t2[@]}"); m4=$(median "${t4[@]}")
    python3 -c "
p, t2, t4, n = $mp, $m2, $m4, $passes
print(f'| $config | {n} | {p:.3f} | {t2:.3f} ({t2 / p:.1f} passages) | {t4:.3f} ({t4 / p:.1f} passages) | {100 * t2 / (n * p):.1f} % | {100 * t4 / (n * p):.1f} % |')"
  done
} > "$out/cost.md"
cat "$out/cost.md"

# The figure: H against w a0 / V for the four models, and the brush's
# closed form (the simplified theory in full adhesion).
.venv/bin/python - "$out" <<'EOF'
import sys, csv
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

out = sys.argv[1]

def load(name):
    rows = [r for r in csv.reader(l for l in open(f"{out}/{name}.csv") if not l.startswith("#"))]
    head, data = rows[0], np.array([[float(v) for v in r] for r in rows[1:]])
    col = {k: i for i, k in enumerate(head)}
    h = lambda k: data[:, col[k + "_re"]] + 1j * data[:, col[k + "_im"]]
    return data[:, 0], h

def brush(w):
    # R_xi(W) = (3/8) int_0^pi sin t int_0^{2 sin t} (2 sin t - s) e^{-iWs} ds dt (brush.rs, eq. 2)
    t, wt = np.polynomial.legendre.leggauss(96)
    out = []
    for W in w:
        total = 0j
        for u, wu in zip(t, wt):
            th = 0.5 * np.pi * (u + 1)
            z = 2 * np.sin(th)
            s = 0.5 * z * (t + 1)
            inner = np.sum(wt * (z - s) * np.exp(-1j * W * s)) * 0.5 * z
            total += wu * np.sin(th) * inner
        out.append(0.375 * total * 0.5 * np.pi)
    return np.array(out)

models = [("exact_fixed", "exact, fixed grid 0.4 x 1 mm", "C0"), ("exact_adapted", "exact, adapted 20 x 20", "C1"),
          ("simplified", "simplified-transient 40 x 40", "C2"), ("fastsim", "FASTSIM 40 x 40", "C3")]
entries = [("fx_creepage_x", r"$H_{x,\xi_x}$"), ("fx_normal_force", r"$H_{x,N}$"), ("fy_spin", r"$H_{y,\varphi}$")]
fig, ax = plt.subplots(2, 3, figsize=(13, 7), sharex=True)
for j, (key, label) in enumerate(entries):
    for name, text, colour in models:
        for f, style in (("2e4", "-"), ("0", ":")):
            if key == "fx_normal_force" and f == "0":
                continue
            w, h = load(f"{name}_f{f}")
            v = h(key)
            ax[0, j].plot(w, np.abs(v) / np.abs(v[0]), style, color=colour, marker=".",
                          label=f"{text}, F_x = {float(f) / 1e3:g} kN")
            ax[1, j].plot(w, np.degrees(np.unwrap(np.angle(v / v[0]))), style, color=colour, marker=".")
    if key == "fx_creepage_x":
        wb = np.linspace(0, 2 * np.pi, 127)
        r = brush(wb)
        ax[0, j].plot(wb, np.abs(r), "k--", lw=1, label="brush closed form (full adhesion)")
        ax[1, j].plot(wb, np.degrees(np.unwrap(np.angle(r))), "k--", lw=1)
    ax[0, j].set_title(f"{label}: |H| / |H(0)|")
    ax[1, j].set_title(f"{label}: phase of H / H(0) (deg)")
    ax[1, j].set_xlabel(r"reduced frequency $\omega a_0 / V$")
    ax[0, j].grid(alpha=0.3)
    ax[1, j].grid(alpha=0.3)
ax[0, 0].legend(fontsize=7)
fig.suptitle("Creep forces' frequency response, paper's scene (N = 100 kN, 100 km/h; solid F_x = 20 kN, dotted 0)")
fig.tight_layout()
fig.savefig("docs/src/figures/creep_response.png", dpi=110)
print("wrote docs/src/figures/creep_response.png")
EOF
