"""The smoke runs of spine.hanzous-brachiation and spine.hanzous-ga (seed 003 §3.3.3–3.3.4, §5.7.3–5.7.5)."""

import numpy as np



def test_hanzous_brachiation_compares_stiff_soft_and_cam_changed(smoke):
    run = smoke("spine.hanzous-brachiation")
    result, out = run.result, run.out
    assert "error" not in result
    m = result["metrics"]
    for policy in ("stiff", "real"):  # the sequence evolved under the cam change misses the bar with a soft trunk
        assert m[f"success_{policy}"] == 1 and m[f"forward_{policy}_m"] > 0.05
        assert m[f"peak_trunk_force_{policy}_n"] > 0 and m[f"grasp_time_{policy}_s"] > 1.0
    assert m["success_soft"] == 0 and m["sequences_played"] == 1 and "seq_stiff.success_soft" not in m
    checks = {c["name"]: c for c in result["checks"]}
    assert {c["row"] for c in checks.values()} == {"003:fig3.13", "003:fig5.23", "003:fig5.24"}
    assert checks["success_real"]["ok"] and m["fitness_real"] > 2.0
    for png in ("trunk_root_force", "trunk_stiffness"):
        assert (out / f"{png}.png").stat().st_size > 10_000
    log = np.load(out / "log.npz")
    assert "real.stiffness_nm_rad" in log and log["soft.stiffness_nm_rad"].max() < log["stiff.stiffness_nm_rad"].min()


def test_hanzous_ga_tiny_budget(smoke):
    """Population 4, the initial generation only, serial (the smoke run): one GA per policy, replayed and recorded."""
    run = smoke("spine.hanzous-ga")
    result, out = run.result, run.out
    assert "error" not in result
    m = result["metrics"]
    checks = {c["name"]: c for c in result["checks"]}
    for policy in ("stiff", "soft", "real"):
        assert m[f"best_fitness_{policy}"] >= m[f"designed_fitness_{policy}"]
        assert checks[f"best_fitness_{policy}"]["ok"] and f"success_{policy}" in checks
        assert (out / f"ga_{policy}.ga.npz").exists()
    with np.load(out / "best_genomes.npz") as f:
        assert f["real"].shape == (70,)
    assert (out / "ga_curves.png").exists()
