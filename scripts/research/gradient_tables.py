"""Markdown tables of reports/gradient_research/*.json (written by scripts/research/gradients.py)."""
import json
from pathlib import Path

D = Path(__file__).resolve().parents[2] / "reports" / "gradient_research"


def angles(path, ests=None):
    rows = json.load(open(path))
    views = list(dict.fromkeys(tuple(r["view"]) for r in rows))
    ests = ests or list(dict.fromkeys(r["estimator"] for r in rows))
    Ss = sorted({r["S"] for r in rows})
    t = {(r["estimator"], tuple(r["view"]), r["S"]): r for r in rows}
    vs = [", ".join(f"{c:g}" for c in v) for v in views]
    out = ["| estimator | S | " + " | ".join(f"({v})" for v in vs) + " | mean | |g|max |",
           "|---|---|" + "---|" * (len(views) + 2)]
    for e in ests:
        for S in Ss:
            cells = [t[(e, v, S)] for v in views]
            mean = sum(c["mean"] for c in cells) / len(cells)
            out.append(f"| {e} | {S} | " + " | ".join(f"{c['mean']:.2f} / {c['max']:.1f}" for c in cells)
                       + f" | {mean:.2f} | {max(c['absmax'] for c in cells)} |")
    return "\n".join(out)


def summary(path, ests=None):
    rows = json.load(open(path))
    ests = ests or list(dict.fromkeys(r["estimator"] for r in rows))
    Ss = sorted({r["S"] for r in rows})
    out = ["| estimator | " + " | ".join(f"S={S}" for S in Ss) + " | all | worst (view, S) mean | max |",
           "|---|" + "---|" * (len(Ss) + 3)]
    for e in ests:
        sel = [r for r in rows if r["estimator"] == e]
        per = [sum(r["mean"] for r in sel if r["S"] == S) / len([r for r in sel if r["S"] == S]) for S in Ss]
        out.append(f"| {e} | " + " | ".join(f"{p:.2f}" for p in per)
                   + f" | {sum(r['mean'] for r in sel) / len(sel):.2f} | {max(r['mean'] for r in sel):.2f} | {max(r['max'] for r in sel):.1f} |")
    return "\n".join(out)


def psnr(path):
    rows = json.load(open(path))
    ests = list(dict.fromkeys(r["estimator"] for r in rows))
    scenes = list(dict.fromkeys((r["volume"], r["scene"]) for r in rows))
    Ss = sorted({r["S"] for r in rows})
    t = {(r["volume"], r["estimator"], r["S"]): r for r in rows}
    out = []
    for key, label in (("psnr", "against the shipped float64 reference (central-difference normals)"),
                       ("psnr_truth", "against the reference with analytic normals (sphere, ml)")):
        out.append(f"\nPSNR (dB) {label}, S = {'/'.join(map(str, Ss))}:\n")
        out.append("| estimator | " + " | ".join(f"{v} ({s})" for v, s in scenes if key == "psnr" or not v.startswith("head")) + " |")
        out.append("|---|" + "---|" * len([1 for v, s in scenes if key == "psnr" or not v.startswith("head")]))
        for e in ests:
            cells = []
            for v, s in scenes:
                if key == "psnr_truth" and v.startswith("head"):
                    continue
                cells.append(" / ".join(f"{t[(v, e, S)][key]:.2f}" for S in Ss))
            out.append(f"| {e} | " + " | ".join(cells) + " |")
    return "\n".join(out)


if __name__ == "__main__":
    print("## summary\n")
    print(summary(D / "angles.json"))
    print("\n## per view (mean / max degrees)\n")
    print(angles(D / "angles.json"))
    print("\n## extra views\n")
    print(angles(D / "angles_extra_views.json"))
    print(psnr(D / "psnr.json"))
