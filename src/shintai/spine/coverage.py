"""Coverage rows of seed 003 (Mizuuchi 2001, variable-flexibility spines), chapters 3–5 and Appendix A, for
``shintai.spine``. Chapter 6 and Appendix C (the middle layer "nervous") are in ``shintai.nervous.coverage``.

One row per experiment or result figure/table. Figures that only show a mechanism, a robot's design, a model or
a block diagram get no row: chapter 2's human-spine figures (Figs. 2.3–2.7), Figs. 3.1–3.3, 3.5 (the optimised
FEM model goes with Table 3.1's row), 3.10–3.12, 3.15–3.26 (except results below), 3.29–3.33, 3.35–3.37,
3.39–3.52, 4.10–4.12, 4.18–4.20, 4.44–4.46, 4.48–4.52, 5.15–5.20, 5.29; design or literature tables (Tables
3.2, 3.3, 4.1, 4.4–4.6, 4.9, 4.10). Figs. 2.1–2.2 (reach with and without a spine) go with Fig. 5.7's row.
Numbers are quoted from the Japanese seed ``003_8568e43d956eb469.txt`` with their section; "no number" means
the thesis shows the result in photographs or plots only. ``not_built`` names the open issue that would build a
row, or says that none does (issues 16 and 17, now built: SQ43 / HanzouS / Cla-crawl whole-body motion and GA;
Cla / Kenta whole-body behaviours, Kenta's taught postures, posture database, motion capture).
"""

from shintai.scenarios.coverage import Row

ISSUE_16 = "issue 16 (Spine robots move their whole bodies: SQ43, HanzouS, Cla crawl)"

ROWS = (
    # ---------------------------------------------------------------- chapter 3: spine structures
    Row(
        key="003:table3.1",
        where="seed 003 §3.2.3, Table 3.1, eqs. 3.1–3.2, Figs. 3.4–3.5",
        what="SQ43's spine reshaped for torsional stiffness: neighbourhood search (the text calls it 最急降下法) "
             "over three vertebra-part angles a1–a3 (|a_i| ≤ 30°, a4 from eq. 3.1), step 0.5°, from the four "
             "starts of Table 3.1 ((5, 5, 5), (−5, −5, 5), (15, 5, −15), (5, −15, 5)°), evaluation = the height "
             "of the lifted left front foot in an FEM + multibody simulation",
        result="§3.2.3: '開始点を設計変数2とした場合の最終評価値が最も高い値'; '開始点が設計変数1及び設計変数3の場合"
               "は，開始後すぐに極小値に陥っている'; '設計変数4を開始点とした場合は最適化の途中から，設計変数1の場合"
               "の最適化とほぼ同一の経路をたどっており，ほぼ等しい評価値で収束' (Fig. 3.4, no number); the chosen "
               "optimum is '一番目の経路で収束した際の設計変数' (ambiguous: the first path, or the best one) and is "
               "shown only as a model (Fig. 3.5)",
        not_comparable="the landscape its search crossed: the FEM model of each shape (§3.2.3 '設計変数から生成された形"
                       "状の脊椎の有限要素モデルをロボットモデルに組み込む': no mesh, material, overall length L or part "
                       "length l), the evaluation time ('ある時刻における左前脚の脚先端の z 軸方向の位置') and Fig. 3.4's "
                       "values; on our compliant-spine stand-in start 3 ends best (8.76 mm; thesis start 2), start 4 joins "
                       "start 2 (thesis: start 1), starts 1 and 3 travel 14° and 25° before stopping (declared 'right "
                       "after starting': ≤ 5°), every start stops on the a4 = ±30° bound (reported, not checked)",
    ),
    Row(
        key="003:fig3.6",
        where="seed 003 §3.2.4 (姿勢制御), Fig. 3.6",
        what="SQ43 keeps its shoulder part level by the 3-axis accelerometers while a board under its left front "
             "leg is raised and lowered (readings used only when steady)",
        result="§3.2.4: the shoulder tilts when the board is raised ('右下がりに傾く'), the left-front leg bend is "
               "adjusted until level (2→3); when lowered the leg extends and the shoulder returns level (4→6). "
               "Photographs only, no number",
        difference="on our MuJoCo SQ43 (a 3-block hinge spine with the quasi-static model's stiffness, chosen "
                   "dimensions, 160 mm track): a 20 mm board (height not in the text) tilts the shoulder 7.1° left-up "
                   "(right-down) without levelling; the steady-window accelerometer controller shortens the left front "
                   "leg until 0.06° (up) and 0.00° (board lowered)",
    ),
    Row(
        key="003:fig3.7",
        where="seed 003 §3.2.4 (クロール歩容), §3.2.5, Fig. 3.7",
        what="SQ43 crawl gait one leg at a time, the CoM shifted away from the swing leg and the leg lifted and "
             "brought forward quickly before the twisting spine lets it touch down",
        result="§3.2.4: lifting a leg from four-leg standing fails ('脊椎のねじれ方向の柔軟性により体幹がねじれ … "
               "脚を持ち上げることができない'); with the CoM over the opposite rear leg and a quick lift it works, "
               "but the lifted posture cannot be held; 'クローラ歩容を実現'. §3.2.5: diagonal two legs could not be "
               "lifted ('対角二脚を持ち上げようとしても脊椎がねじれて脚が上がらなかった'). No number",
        difference="on our MuJoCo SQ43: a 30 mm lift of the right front leg from standing reaches 13 mm (the spine "
                   "twists 10°); after shifting the CoM halfway toward the left hind foot 28 mm, sinking to 16 mm "
                   "when held 1 s; a diagonal pair reaches 15 mm; with the torsion hinges removed (ablation) 26 mm and "
                   "31 mm. The slow planned crawl (1 s CoM shifts, quick 0.28 s swings) walks 105 mm in two cycles",
    ),
    Row(
        key="003:fig3.8",
        where="seed 003 §3.2.4 (不整地歩行), Fig. 3.8",
        what="SQ43 crawls over unknown uneven ground: on touchdown a non-level shoulder or hip (accelerometers) "
             "pauses the gait, the leg bends are adjusted until level and the gait continues relative to them",
        result="§3.2.4: on a height change the shoulder tilt is detected and the left front leg bent (2→3) or "
               "extended (5→6) to level it; the spine's torsional compliance lets all four feet touch "
               "('四脚全てを接地することができる'). Photographs only, no number",
        why_not="on our MuJoCo SQ43 over a 15 mm block under the left feet (height not in the text) the levelled "
                "crawl holds (153 mm; LF shortened 12.4 mm stepping up, extended back stepping down; four feet down "
                "and shoulder/hip within 0.63° after all 12 pauses; a trunk rigid in torsion lifts a foot at the "
                "step), but without the levelling the foam spine keeps four feet down at the step (5.8° tilt) and "
                "then tips over a cycle later, failing the declared four-feet-at-every-touchdown check",
    ),
    Row(
        key="003:fig3.9",
        where="seed 003 §3.2.4 (立ち上がり動作), Fig. 3.9",
        what="SQ43 stands up from lying on the floor by a human-found sequence alternately extending front and "
             "hind legs with the spine assisting, recorded and replayed",
        result="§3.2.4: extending all legs at once cannot lift the body (leg torque too small); the trial-and-error "
               "sequence, replayed from its log, stands the robot up. Photographs only, no number",
        why_not="on our MuJoCo SQ43 with the leg servos at the S9204's 12.6 kgf·cm (§3.5.1, Rabbit's servo: the seed "
                "names none for SQ43) every strategy stands, all legs at once too (needs 0.64 N·m); the arched-spine "
                "turns first stand at 0.58 N·m but fall again at 0.84–0.86, so reliably only from 0.86 N·m; the "
                "thesis's pair of results holds only for a servo of 0.58–0.64 N·m",
    ),
    Row(
        key="003:fig3.13",
        where="seed 003 §3.3.3–3.3.4, Figs. 3.13–3.14",
        what="HanzouS (18 joints, 1-DOF leaf-spring trunk whose stiffness a cam changes) brachiates: stiffest "
             "while pulling the legs back, changed to softest between releasing the rear bar and reaching the next",
        result="§3.3.4: 'ブラキエーション動作のバー把持時の衝撃力を脊椎の柔軟性により緩和されている' (Fig. 3.14, no "
               "number); '体幹を最も剛な状態にしておくことにより, 重心を後に持ってくる事ができている'",
        difference="on our simulated HanzouS (joint layout, sizes, leaf and bars chosen; planar, hook grip), not the "
                   "robot, by tiny margins: the grasp's impact (peak trunk-root force in the 0.3 s after it) 8.02 N "
                   "stiff against 7.96 N with the cam-changed trunk (0.7 %); the stiff trunk brings the centre of "
                   "mass 0.25 mm further back (−10.6 against −10.4 mm) while the legs are pulled back",
    ),
    Row(
        key="003:fig3.27",
        where="seed 003 §3.5.4, Fig. 3.27",
        what="Rabbit turns its upper body with its 6-muscle, 5-ball-joint silicone-disc spine",
        result="§3.5.4: '脊椎構造が、上半身の重量を十分支えて旋回を行うことができることを確認した'. Photographs "
               "only, no number",
        difference="on the quasi-static Rabbit (chosen disc law, upper body 0.5 kg 30 mm ahead of the axis, not "
                   "measured), not a dynamic body: the discs pre-compressed 1 mm, the muscles turn the top through "
                   "76.3° of a commanded ±40° (0.95) while it tilts at most 0.34° and the muscles pull 26 N of the "
                   "servo's 124 N; on the soft (not pre-compressed) spine the same command turns it 35.7° (0.45)",
    ),
    Row(
        key="003:fig3.28",
        where="seed 003 §3.5.3–3.5.4, Figs. 3.26, 3.28",
        what="Rabbit's spine stiffened by pulling all six muscles so the silicone discs (KE-106, JIS-A 50) are "
             "pre-compressed; pushed from the side, upright",
        result="§3.5.3: 'シリコンゴムの非線形性のため、挙動 2 における弾性部品の弾性係数は挙動 1 におけるそれよりも"
               "大きい … 挙動 2 の脊椎は、挙動 1 の脊椎よりも硬くなる'; §3.5.4: '外部からの力に対しての剛性が増す"
               "．このことを脊椎を横から押すことで確認した (Fig. 3.28)' — soft vs hard photographs, no number",
        difference="stiffer when pulled, as claimed (0.71 → 8.45 N/mm, ×11.9, on a quasi-static model with a chosen "
                   "cubic disc law — no silicone curve in the text; a linear disc stiffens too, ×4.7, from the taut "
                   "muscles); the size has no thesis number and the nonlinear share follows from the chosen law",
    ),
    Row(
        key="003:fig3.34",
        where="seed 003 §3.6.1, Fig. 3.34",
        what="Cla's FSR tension sensors (#400, #402) calibrated: applied tension against the 10-bit ADC value, "
             "read 10 s after loading",
        result="§3.6.1: '小さい力の領域で分解能が高く大きい力の領域で分解能が粗い'; drift over time, so absolute "
               "accuracy is low but relative readings are usable. Plot only, no number",
        not_comparable="Fig. 3.34's calibration points (counts against tension for the #400 and #402 sensors: a plot "
                       "only) nor Fig. 3.33's l, b and k: spine.tension-sensor sweeps our one sensor (eq. 3.3, chosen "
                       "constants, 10-bit ADC) — one count is 0.035 N at 1 N, 0.67 N at 100 N and 4.4 N at 300 N (×124), "
                       "the property §3.6.1 states, which our constants were chosen to have (consistency checks)",
    ),
    Row(
        key="003:fig3.38",
        where="seed 003 §3.6.3, Fig. 3.38",
        what="Cla takes twist and lateral-bend postures",
        result="§3.6.3: 'ねじりや側屈の稼働範囲により，脊椎が無ければ不可能であるような姿勢を可能にしている'. "
               "Photographs only, no number",
        why_not="on the seated whole-body MuJoCo Cla (muscle spine, L mode) with four poses of ours, the hand targets "
                "from the model: both 72° side bends (71.5° reached) and the 60° twist (54.6°) put the hand within "
                "2.8–3.1 cm of its target, which the arm alone misses by 8.8–12.6 cm with the spine locked; but the "
                "twist with a side bend (45°, −45°) reaches roll 52.5°, yaw −18.8°: three of the eight muscles go slack, "
                "the bend gathers in the middle joints (15–16° roll each of the 9° commanded) and the hand ends 13.8 cm "
                "off (declared 5 cm), so 3 of 4 poses (notes/cla-poses.md)",
    ),
    Row(
        key="003:fig3.53",
        where="seed 003 §3.7.6, Fig. 3.53",
        what="Kenta (tendon-driven humanoid, 10-segment spine with muscles to middle vertebrae) moves its spine",
        result="§3.7.6: '全身の動きを利用した人間の動きに近づいた動きを可能にしている様子が見られる'. Photographs "
               "only, no number",
        difference="our whole-body Kenta (spine/kenta/body.py: the 40 muscles and ligaments of robots.py with chosen "
                   "attachment points, servoed arms, a wire-sum neck, pan/tilt eyes; no legs, pelvis fixed) moves its "
                   "spine into three taught postures (spine.kenta-taught-postures) and back, within 2° of them; discs "
                   "280 N m/rad = 2 × the stiffness that makes upright stable under gravity with all muscles at 1 kgf "
                   "(§7.1.1's criterion: not a thesis number); the teacher reaches only half the commanded bend",
        why_not="the replayed postures miss the taught ones (mean error > 5°) (notes/kenta-taught-postures.md)",
    ),
    # ---------------------------------------------------------------- chapter 4: control of the spine
    Row(
        key="003:fig4.1",
        where="seed 003 §4.2.2 (複数の姿勢の教示による動作の実現), Fig. 4.1",
        what="three postures taught to Kenta (all muscles tension-controlled) and replayed in turn with "
             "interpolation",
        result="§4.2.2: '腱太(第 3.7節参照)に三種類の姿勢を教示し，それを順に繰り返し再生する様子を Fig. 4.1 に示す'. "
               "Photographs only, no number",
        difference="the teacher is a pair of hands holding every spine joint (position servos on the hinges) while "
                   "all 40 muscles run T mode at 1 kgf; three chosen postures, replayed through the seqplugin "
                   "player (minimum jerk, 1 s moves every 2 s), two cycles; discs 280 N m/rad (2 × the stiffness "
                   "that makes upright stable under gravity with all muscles at 1 kgf, §7.1.1's criterion), so the "
                   "teacher reaches only 6–9° short of the commanded postures; replayed within 1.3° (mean)",
        why_not="replayed postures not nearest their own taught ones (notes/kenta-taught-postures.md)",
    ),
    Row(
        key="003:s4.2.2",
        where="seed 003 §4.2.1–4.2.2 (動作の直接教示); 20 ms sampling from §5.9.2",
        what="direct motion teaching on Cla: all muscles held at a constant tension (e.g. 1 kgf, §4.2.1), a human "
             "moves the spine, the encoder log is replayed as targets, sped up by taking every 2nd, 3rd … sample",
        result="§4.2.2: 'ログから 1 つおきにデータを取り出し再生すると倍の速さで動作した。2つおきにすると3倍になった"
               "。4倍・8倍も試行したところ、4倍は4倍の速さで動作したが、8倍はモータの最高速度を超えたようで、速い動"
               "作の部分は追従しきれなかった' — no error number, no demonstration speed",
        not_comparable="the taught motion's speed or its encoder log, or any replay error (§4.2.2: 'その時のエンコーダの"
                       "ログを記録した' — the log is not shown; '8倍はモータの最高速度を超えたようで' rests on that speed): "
                       "ours (15 mm/s peak muscle speed) was chosen inside the band the outcome implies (10.4–20.7 mm/s, "
                       "1/8–1/4 of Table 3.2's 82.9 mm/s), so 2–4× tracking (0.9–2.9 % error) and 8× saturation (37 % "
                       "of ticks) follow from it",
    ),
    Row(
        key="003:table4.2",
        where="seed 003 §4.4.3 (ヤコビアン逆行列を利用), Table 4.2, eqs. 4.26–4.28",
        what="muscle lengths → posture on Cla's geometric model by integrating the pseudo-inverse muscle-length "
             "Jacobian, for uniform bends of 1, 5 and 10°/segment about each axis, 3 division counts each",
        result="Table 4.2: mean |error| per axis from 0.0 to 304 °/segment (mostly tens to hundreds), maxima up "
               "to ±360°; computing times 19.4–2100 s; §4.4.3 '誤差は非常に大きく、計算時間も非常にかかる'; 各手法の比較: "
               "'誤差も NN を利用する場合と比較して大きい'",
        difference="our integration errs 12.9° mean norm (24.4° max) on 50 random postures — tens of degrees, not "
                   "hundreds: Cla's J_m has rank 6 (8 muscles, 15 DOF) and it lands on another posture; 21 ms per "
                   "posture (the thesis's 19–2100 s on 2001 hardware)",
    ),
    Row(
        key="003:table4.3",
        where="seed 003 §4.4.3 (ニューラルネットワーク), Table 4.3, Figs. 4.2–4.9",
        what="NN 8 muscle lengths → 15 joint angles trained by back-propagation (eq. 4.30) on 343 uniform-bend "
             "postures (φ, θ, ψ ∈ {−15 … 15}° in 5° steps); 8 architectures; 50 random uniform-bend test postures",
        result="Table 4.3 minimum error norms: 8-10-10-15 1.12 (random inputs: mean 2.51), 8-12-15 4.73, 8-20-15 "
               "1.58, 8-30-15 1.35, 8-40-15 1.26 (random: 1.95), 8-50-15 1.75, 8-70-15 4.71 and 8-100-15 10.9 (not "
               "converged); the 4-layer net reproduces the teacher data better but generalises worse, so 8-40-15 "
               "is chosen; '関節誤差の最大値は … (8-40-15) の層構成の場合、0.5° 未満程度'",
        difference="trained by L-BFGS (the thesis: back-propagation), two of the eight architectures: 8-40-15 "
                   "0.18° on the test postures (thesis 1.95°), 8-10-10-15 0.35° (2.51°), max joint error 0.19° "
                   "(< 0.5°); on the teacher data the 4-layer net is worse (0.31° vs 0.14°), the opposite of "
                   "Table 4.3's 1.12 < 1.26",
    ),
    Row(
        key="003:fig4.13",
        where="seed 003 §4.5.2 (ソフトウェアばね制御の様子), eq. 4.36, Figs. 4.13–4.17",
        what="all 8 of Cla's muscles in software-spring (S) mode, l_0 = the basic posture's lengths, k_s = 50, 100, "
             "200, 400 (ADC counts per encoder pulse); a human bends the spine and lets go",
        result="§4.5.2: '人間が脊椎の姿勢を変えて手を離すと戻る' (Fig. 4.13); Figs. 4.14–4.17: 'バネ定数が大きいほど"
               "筋長の変化が小さくても張力の変化は大きくなる様子がわかる'. Plots only, no number",
        difference="the hand is an imposed 8° roll-and-pitch displacement (ours), so only the tension half of the "
                   "claim is exercised (1.8 / 5.1 / 15.0 / 35.5 N/mm at k_s = 50–400 with our chosen unit scale, "
                   "30 N/m per count ratio at rest); released, the spine returns within 0.52°",
    ),
    Row(
        key="003:table4.7",
        where="seed 003 §4.7.2, Table 4.7, Figs. 4.21–4.27",
        what="Cla with both arms raised straight up, whole-spine pitch 0 → −30 → +30 → 0° then roll likewise in "
             "10° steps (keyboard-paced, several seconds each) under 8 control-mode combinations; mean |posture "
             "error| per posture from the shoulder and waist accelerometers (eq. 3.4)",
        result="Table 4.7: per-posture mean errors 0.03–18.48°, e.g. all-L pitch −10 … 0: 0.65, 2.83, 4.17, 9.33, "
               "7.17, 4.20 — larger on the way back; '—' where the spine could not hold and the experimenter "
               "supported it by hand; L + T buckled, no data. (Its columns order S-high before S-mid; §4.7.2 says "
               "'7種類' for the 8 listed modes)",
        why_not="with the pre-compressed hardening discs (2 × the upright criterion's k*, §7.1.1) and the muscles "
                "bearing on the column, Table 4.7's '—' (the spine caught by hand) starts where ours is lost in 11 of 14 "
                "sequences (5 before), but all-L's errors are still 6× and 15× smaller (0.95° / 0.24° pitch / roll against the table's "
                "5.40° / 3.68°; 4 of 14 mode–axis means within the declared 2°): the wrapped muscles are the lengthening "
                "ones, slack by more than the 0.29 mm the column adds, so all-L's error is the same without it; "
                "muscle–muscle contact is not representable. The thesis's own tables disagree: Table 4.7's column means "
                "against Table 4.8's (§4.7.3 'Table 4.7 から誤差の平均を求めた') — roll all-LL 4.09 / 2.93 and L + LL "
                "2.93 / 4.09 (two columns swapped), pitch off by up to 1.95° (L + S-high 4.92 / 6.87)",
    ),
    Row(
        key="003:table4.8",
        where="seed 003 §4.7.3, Table 4.8",
        what="summary of the same experiment per mode: mean model error, largest posture held, mean tension and "
             "mean current, pitch and roll",
        result="Table 4.8 (pitch / roll): 1. all L 4.73/3.68°, held ≥30/≥30, 0.20/0.13 kgf, 0.41/0.33 A; 2. all LL "
               "2.85/2.93, 10/≥30, 0.48/0.47, 0.59/0.64; 3. all S mid 4.83/4.06, 20/≥30, 0.13/0.13, 0.49/0.42; 4. "
               "all S high 3.86/4.17, ≥30/≥30, 0.23/0.25, 0.98/0.79; 5. L + LL 3.66/4.09, 10/≥30, 0.09/0.24, "
               "0.25/0.38; 6. L + T buckled ('座屈してデータ取れず'), 0/0; 7. L + S mid 5.88/4.93, ≥30/≥30, "
               "0.26/0.41, 0.86/0.99; 8. L + S high 6.87/4.47, ≥30/≥30, 0.25/0.33, 1.29/1.04. §4.7.3: LL, S-mid "
               "and L + LL cannot hold large pitch against gravity; modes 7 and 8 have larger errors and mean "
               "currents",
        why_not="with the pre-compressed hardening discs (Rabbit's ring law; tangent at rest 2 × the upright "
                "criterion's k* = 12.4 N m/rad, §7.1.1/§4.6.2) and the muscles bearing on the column, 11 of 16 held-angle "
                "cells agree (6 on linear discs; 12 with the discs alone): every roll cell and all-L, all-S-high, "
                "L + S-mid pitch ≥30, all-LL pitch 10; not: all-S-mid holds pitch to 30 (thesis 20), L + LL (0, thesis "
                "10) and L + S-high (10, thesis ≥30; ≥30 without the column) are lost still drifting on the way back "
                "from −30, and L + T "
                "no longer buckles (30 / 30, thesis 0 / 0: every muscle at one tension is the criterion's stable state); "
                "L + S draws the least current, not the most (0.027 vs 0.042 A). The thesis's Tables 4.7 and 4.8 "
                "disagree with each other (two roll columns swapped; pitch means off by up to 1.95°)",
    ),
    Row(
        key="003:tableA",
        where="seed 003 App. A.2, Tables A.1–A.28, Figs. 4.28–4.41",
        what="per-muscle mean and maximum tension and motor current per posture and mode of the Table 4.7 "
             "experiment (current through the 0.1 Ω series shunt of the JSK-D02 driver, §3.6.2, §4.7.2)",
        result="Tables A.1–A.14 tensions (kgf), A.15–A.28 currents (A); e.g. Table A.15 (all L) HIP-RB at pitch "
               "−20 (returning) 3.82 A mean; per-muscle posture means reach 7.92 A (A.20, L + S mid), maxima "
               "10.08 A (A.27); blank where the spine collapsed and was held by hand; L + T "
               "'データを取ることができなかった'",
        not_comparable="the currents' read-out scale: §3.6.2 gives only I = V/R across the 0.1 Ω shunt (eq. 3.6), not "
                       "how V was amplified and converted, and the printed 'A' cannot be amperes — 221 of the 1,200 "
                       "per-muscle posture means exceed the 1.1 A stall current derived from Table 3.2 (up to 7.92 A); "
                       "the tensions (A.1–A.14, kgf, through Fig. 3.34's unprinted calibration) were used to build the "
                       "model (clavicle height, routing), so they cannot also test it",
    ),
    Row(
        key="003:fig4.42",
        where="seed 003 §4.7.4, Figs. 4.42–4.43",
        what="Cla's spine commanded in roll, pitch and yaw on the geometric model and controlled on the robot",
        result="§4.7.4: model posture (Fig. 4.42) and the controlled robot (Fig. 4.43) shown side by side. "
               "Photographs only, no number",
        difference="on the seated whole-body MuJoCo Cla (arms resting, L mode), three combined postures of ours "
                   "((20, 15, 30), (−20, 15, −30), (15, −10, 20)° roll, pitch, yaw; the thesis prints none): every axis "
                   "within 4.72° of the command (bound declared: Table 4.8's all-L 4.73°), the shortfall all in yaw "
                   "(−4.5°, +4.7° of ±30°) and pitch (+3.0°); joints 1.0–1.7° RMS from the model's uniform bend",
    ),
    Row(
        key="003:fig4.47",
        where="seed 003 §4.8.2, Fig. 4.47",
        what="contraction force against contraction ratio at constant pressure of the home-made McKibben muscle and "
             "the Shadow Air Muscle used in BeBe",
        result="Fig. 4.47: characteristic curves only, no number in the text",
        not_comparable="the curves' values or the constant pressure they were taken at (§4.8.2 '各々の内圧一定での収縮"
                       "力と収縮率の関係を Fig. 4.47 に示す' — a plot only): our BeBe plant's McKibben law is chosen "
                       "(linear, 30 N at no contraction to 0 at the 30 % stroke; spine.bebe-tracking's mckibben_force_at_* "
                       "metrics)",
    ),
    Row(
        key="003:fig4.53",
        where="seed 003 §4.8.3, Figs. 4.52–4.53",
        what="BeBe: the image shift v_i of a target when only muscle i is switched on, for each of the 36 muscles; "
             "and whether two muscles' shifts superpose",
        result="Fig. 4.53: the v_i field and the same/inverse-direction split (plot only); §4.8.3: '実験の結果、BeBe "
               "は単純な重ね合わせは適用できない構造であることがわかった [38]'; hysteresis present",
        not_comparable="the 36 measured shifts v_i (§4.8.3 'Fig. 4.53 は各筋に対応する v_i をプロットした図である' — a "
                       "plot only), the muscle arrangement of Table 4.10 (not in the text) or [38]'s superposition "
                       "numbers: spine.bebe-tracking measures our plant's v_i the same way, and its non-superposition and "
                       "hysteresis checks test properties built into our plant (consistency)",
    ),
    Row(
        key="003:fig4.54",
        where="seed 003 §4.8.4 (通常のトラッキング動作), Fig. 4.54",
        what="BeBe tracks a visual target with its 36 on/off muscles: off the most opposed inverse-direction "
             "muscle first, else on the best same-direction one (cos θ_i = 0.2), dead zone at the centre, 66 ms "
             "image period",
        result="§4.8.4: '人間が普通に対象物を動かす程度の速さであればしっかり対象物を追跡し続けることができた'; "
               "'時折画像の中心を往復する形で二つの姿勢を繰り返す' (attributed to no solution inside the dead "
               "zone). No number",
        difference="our lumped BeBe plant; dead zone 15 px and a target at up to 0.13 m/s are ours: target inside "
                   "the dead zone in 71 % of image cycles, never beyond 39 px, ≤ 5 muscles on, 34 two-posture "
                   "reversals",
    ),
    Row(
        key="003:fig4.55",
        where="seed 003 §4.8.4 (外乱を受けながらのトラッキング動作), Fig. 4.55",
        what="BeBe keeps tracking while a person pushes the middle of its spine left and right",
        result="§4.8.4: '人間に手で左右に押されながらも，対象物を視野の中心に保っている様子がわかる'. No number",
        difference="8 lateral pushes of 40 N (ours) on the spine's middle: each recovered within 0.29 s",
    ),
    Row(
        key="003:fig4.56",
        where="seed 003 §4.8.4 (制約条件下でのトラッキング動作), Fig. 4.56",
        what="BeBe tracks with some muscles forced on (case 1: muscles tilting the spine left; case 2: tilting it "
             "back), the free muscles driven by the same rule",
        result="§4.8.4: forcing the muscles on moves the target off the centre, then '制約の課されていない筋群のみを"
               "操作して再び対象物が視野の中心になるような姿勢を取っている' (both cases). No number",
        difference="target re-centred to 8.3 px (left) and 6.2 px (back) within the 15 px dead zone, in 0.32 s and "
                   "0.45 s; which muscles were forced is ours",
    ),
    # ---------------------------------------------------------------- chapter 5: whole-body behaviour
    Row(
        key="003:fig5.1",
        where="seed 003 §5.2.1, Fig. 5.1",
        what="Cla bends sideways, forwards/backwards and twists with the arms coordinated, seated",
        result="§5.2.1: seated on a chair too high for the feet to touch the floor, bending sideways brings the hand "
               "'ほぼ足裏の高さと同程度の高さまで到達'; arms coordinated so they do not hit the body. Photographs",
        difference="on the seated whole-body MuJoCo Cla (muscle spine, L mode; soles 26.5 cm above the floor), side "
                   "bends of 72° (ours; 71.5° reached) with the arm solved on the model to reach straight down: the "
                   "hand's lowest point 0.3 cm below the soles' on both sides (declared: within 5 cm); spine locked, "
                   "11.5 cm above. The front–back and twist bends and the arms' coordination against hitting the body "
                   "(our arms do not collide with the trunk) are not tested",
    ),
    Row(
        key="003:fig5.2",
        where="seed 003 §5.2.2, Fig. 5.2",
        what="Cla levels its shoulders by the 3-axis accelerometers, estimating its spine posture with the NN "
             "length → posture model (§4.4.3), sensing and moving in alternate phases",
        result="§5.2.2: the spine is controlled until the shoulders are level. Photographs, no number",
        difference="on our whole-body MuJoCo Cla (muscle spine, L mode) the disturbance is ours, a stool tilted "
                   "10° in roll, then to (−6°, 8°) in roll and pitch: the shoulders settle within 0.3° of level "
                   "(10° and 11° without levelling) after two sense → NN posture → move rounds per tilt; a round "
                   "sensed while the stool was still moving overshoots once (−14°)",
    ),
    Row(
        key="003:fig5.3",
        where="seed 003 §5.2.3, Figs. 5.3–5.4",
        what="Cla throws an object with the spine (spine root, then shoulder, then elbow) and without it",
        result="§5.2.3: '脊椎を利用しない場合は肩から手先までの関節しか加速に利用できないため、脊椎を利用する場合に"
               "比べ手先の最大速度は小さくなる'. No measured speed",
        difference="on our seated MuJoCo Cla with chosen postures and durations (spine 0.6 s, shoulder 0.3 s, "
                   "elbow 0.2 s, peaks aligned): peak hand speed 3.96 m/s with the spine, 3.49 m/s with it locked "
                   "(×1.13), 3.84 m/s with the spine but all parts started together; the muscles turn the spine "
                   "41° of the 60° commanded",
    ),
    Row(
        key="003:fig5.5",
        where="seed 003 §5.2.4, Figs. 5.5–5.6",
        what="Cla pulls an object on a desk towards itself, with and without the spine",
        result="§5.2.4: without the spine '手が対象物に届かない' (Fig. 5.6); with it, it succeeds; the spine posture "
               "was tuned on the robot. Photographs",
        difference="on our MuJoCo Cla (fingerless hand hooking a 40-mm cube set 5 mm beyond the straight-spine "
                   "reach, 70° lean commanded, 66° reached) with the spine's posture tuned as the thesis's was "
                   "('脊椎の姿勢は実機で調整し決定している'): a +8° yaw held while leaning, chosen on the hand's lateral "
                   "drift (2.3 cm, against 4.5 cm untuned), drags the cube 13.0 cm (untuned 4.9 cm, under our 5 cm; "
                   "every offset 2–14° passes); spine locked, the hand stays 4.8 cm short",
    ),
    Row(
        key="003:fig5.7",
        where="seed 003 §5.2.5–5.2.6, Fig. 5.7 (and §2.1.4, Figs. 2.1–2.2)",
        what="Cla, seated, picks an object off the floor by bending sideways and puts it on the desk by twisting",
        result="§5.2.5: by the spine's roll DOF Cla picks the object '重心を椅子の上に置いたまま'; a humanoid without "
               "a spine would have to roll its hip unnaturally and lose its balance (Fig. 2.1: the conventional "
               "humanoid does not reach the floor); §5.2.6: without moving the spine the object cannot be put on the "
               "desk. Photographs",
        why_not="on the muscle-spine MuJoCo Cla seated with the floor 1 cm under its soles: a 70° side bend brings "
                "the hand onto the object (the arm alone stays 9 cm short), the CoM stays ≥ 5 cm inside the seat's "
                "sides, a 56° twist puts it on the desk 4.5 cm from the chosen spot; but without the spine the arm "
                "still gets over cla_body's desk (near edge 12 cm in front), so §5.2.6's 'cannot place without the "
                "spine' does not reproduce; the hand closes by a weld; Fig. 2.1's hip-roll comparison is not made "
                "(Cla has no hip roll)",
    ),
    Row(
        key="003:fig5.8",
        where="seed 003 §5.2.7, Fig. 5.8",
        what="Cla stands (lifted up by a person, servo errors watched) and bends sideways while swinging both arms "
             "forward/back to keep the sole centre of pressure near the foot centre",
        result="§5.2.7: with that reflex in parallel with the side bends '立った状態での運動ができるようになった'. "
               "No number",
        difference="on the muscle-spine MuJoCo Cla (standing start, the stand-up from the chair not simulated): with "
                   "the reflex the CoP's front–back excursion is 8.7 mm (RMS 3.5) against 11.0 mm (RMS 7.8) without "
                   "it, through ±30° side bends; without the reflex our Cla does not fall either (no mechanical play "
                   "in the model), so the reflex centres the CoP rather than saving the stance",
    ),
    Row(
        key="003:fig5.9",
        where="seed 003 §5.2.8, Fig. 5.9",
        what="Cla rolls over on the floor, yawing the spine together with shoulders and hips",
        result="§5.2.8: hip and shoulder power alone cannot raise half the body; with the spine's yaw "
               "'仰向けからうつぶせ、うつぶせから仰向けと、両方向の寝返りができるようになった'",
        why_not="on the muscle-spine MuJoCo Cla, hand-made keys from the back: the spine's twist raises the shoulders "
                "54° against 1.3° locked ('半身を起こす' reproduces) but the pelvis stays down; keys searched by seed "
                "003's GA (23 genes, 12 × 12): the spine carries both halves past the side (pelvis 126°, shoulders "
                "144°; locked 89°) but not onto the front (our 135°); from the front the hand-made keys roll Cla onto "
                "its back, with the spine locked too (the arms push on the floor), against §5.2.8's need of the spine",
    ),
    Row(
        key="003:fig5.10",
        where="seed 003 §5.2.9, Fig. 5.10",
        what="Cla crawls on hands and knees with a hand-made pattern, rolling the spine with the limbs",
        result="§5.2.9: without the spine's twist the hips and shoulders cannot be raised; the hand-made pattern "
               "'なかなか速く進む動作パターンを作ることができなかった. また, 真っ直ぐに進まずに曲がって進む事も多かった'",
        difference="on a servoed-spine MuJoCo Cla that starts kneeling (the lift from prone, which needs the "
                   "spine's twist, is not simulated) with a hand-made pattern of ours: the roll lengthens the stroke "
                   "(0.128 against 0.093 m per cycle with the spine locked) and the crawl veers more (6.1° against "
                   "2.4°), but the servoed spine costs more torque than a rigid trunk (64 against 13 N m s in 8 s)",
    ),
    Row(
        key="003:fig5.11",
        where="seed 003 §5.2.9, Fig. 5.11",
        what="Cla's crawl optimised by a GA in the fast physics environment (§5.4.5): genes = the spine's roll "
             "amounts and timings (limbs fixed, time-scaled), fitness = forward distance, torque integral, peak "
             "torque",
        result="§5.2.9: a pattern optimised '少なくともシミュレーション環境用には' is shown crawling (Fig. 5.11). No "
               "fitness value or curve",
        difference="the spine's joints servoed directly (not its muscles), our 4-phase pattern and fitness weights; "
                   "the budget a stopping rule declared before the run (best < 1 % better over 20 generations; the "
                   "thesis prints no generation count): seed 0 stopped at 68 generations, fitness 0.24 → 0.46, the "
                   "evolved crawl goes 0.52 m in 8 s against the hand-made 0.43 m and the rigid spine's 0.31 m, drift "
                   "1.7° (200 generations: 0.57 m); gains are in distance, not torque; a plateau of 18 generations "
                   "(19–37) came near the window, so the verdict leans on its size",
    ),
    Row(
        key="003:fig5.12",
        where="seed 003 §5.2.10, Fig. 5.12",
        what="Cla tracks a coloured target with neck (pan/tilt) and spine (pitch/yaw from the NN posture) "
             "routines run in parallel",
        result="§5.2.10: realised by tuning the two routines' gains. No number",
        difference="the whole-body Cla (spine/cla/body.py) seated; the colour-region detection replaced by the ball's "
                   "centre projected into the head camera; the spine's posture from the muscle lengths by Cla's "
                   "8-40-15 NN (§4.4.3); neck loop 66 ms, spine loop 198 ms, gains chosen: over an 8 s ±18° sweep the "
                   "ball stays in view, RMS 4.1° off axis (max 6.1°), neck 75 % / spine 25 % of the pan, the NN's "
                   "estimate within 1.3° of the true whole-spine posture; by Jacobian integration instead (the "
                   "'cla-jacobian' run) Cla tracks as well (RMS 4.0°, estimate within 0.9°)",
    ),
    Row(
        key="003:fig5.13",
        where="seed 003 §5.2.11, Fig. 5.13",
        what="Kenta moves spine, neck and both arms at once",
        result="§5.2.11: shown in photographs only, no number",
        difference="spine.kenta-spine-neck-arms: the spine through three whole-spine key postures (ours) by the "
                   "forward model alone (eq. 4.25, L mode, linear player), the neck's pan/tilt and both arms swinging "
                   "(ours); in every 0.5 s window each of spine, neck and each arm turns by more than 1° (fraction "
                   "1.00); the spine sweeps 23°, reaching 86 % of each commanded bend (3.1° short on average: the "
                   "muscles against the stiff discs)",
    ),
    Row(
        key="003:fig5.14",
        where="seed 003 §5.2.12, Fig. 5.14",
        what="Kenta tracks a target with eyes, neck and spine: three visual-feedback loops of different periods in "
             "parallel",
        result="§5.2.12: realised ('実現している'); no period or error printed",
        difference="our whole-body Kenta; eye loop 33 ms, neck 66 ms, spine 198 ms (periods not in the text: chosen), "
                   "each a Module of one Loop; the ball's centre projected into the left eye camera; the spine's "
                   "posture by Kenta's own NN (§4.4.3's method, 40-40-30 on 343 uniform bends of ±9°/joint: ours, the "
                   "thesis prints none for Kenta): in view 100 %, RMS 1.0° (max 1.5°), the estimate within 0.7°, eyes "
                   "78 % / neck 15 % / spine 6 % of the pan. Jacobian integration (eqs. 4.26–4.28) reading the same "
                   "run's lengths beside the NN diverges 0.59 s in (1616° whole-spine error); driving the spine "
                   "instead (the kenta-jacobian run) it diverges 0.40 s in (2402°), the spine sits on its clip and "
                   "the eyes and neck track alone (in view 99.4 %, RMS 4.1°, max 34.5°)",
    ),
    Row(
        key="003:fig5.21",
        where="seed 003 §5.6.2, Fig. 5.21",
        what="SQ43 trot generated by a parallel GA on the DADS + ANSYS simulator: 6 genes (cycle 2.0–4.0 s, fore "
             "40–80 mm, natural length 208–228 mm, height 5–25 mm, leg centres front/rear −30–30 mm; duty 0.5, "
             "start times 0 and 1.5 s), population 20, crossover 0.2, mutation 0.02, culling 0.4",
        result="§5.6.2: 'パラメータが多くないからか，それほど世代数をかけずに学習が収束している'; '1 個体の数秒間の"
               "運動の解析に約 30 分程度'. Curve only (Fig. 5.21), no generation count",
        difference="on our MuJoCo SQ43 (not DADS + ANSYS), fitness weights ours (distance − 2 mm/deg × twist − "
                   "0.5 × swing height): 0.06 s per individual (~3 × 10⁴× faster than 30 min); the budget a stopping "
                   "rule declared before the run (best < 1 % better over 20 generations): seed 0 stopped at 50, the "
                   "best 180 → 202 by generation 18, 204.5 at 29 (227 mm in 6 s)",
        why_not="'few generations' is not met on our measure (95 % of the gain by half the run): 95 % came at "
                "generation 29 of 50; the curve flattens early as Fig. 5.21's, but the thesis prints no number",
    ),
    Row(
        key="003:fig5.22",
        where="seed 003 §5.6.3, Fig. 5.22",
        what="the GA's trot run on the simulator and on the real SQ43",
        result="§5.6.3: on the real robot the legs tend to drag and the direction does not fully match the "
               "simulator: '…一致はしなかったが，歩行に成功した'. Photographs",
        difference="the simulated half only (the real robot cannot be rebuilt): spine.sq43-trot-ga replays the GA's "
                   "best trot on the body (227 mm forward in 6 s, drifting 82 mm sideways) and films it with --video",
    ),
    Row(
        key="003:fig5.23",
        where="seed 003 §5.7.3–5.7.4, Fig. 5.23",
        what="HanzouS brachiation reproduced in the modified-DADS simulator (stiffness changed during the motion, "
             "eqs. 5.4–5.8), GA over 70 genes (9 joints + 1 time step × 7 transitions of an 8-posture spline), "
             "population 105, crossover 0.2, mutation 0.02, culling 0.4",
        result="§5.7.4: real and simulated motions differ slightly ('若干の違いがある') but the difference in impact "
               "force with stiffness can be seen. Photographs",
        difference="MuJoCo with the trunk stiffness E I / l (Eq. 5.8's bending block) rewritten between steps instead "
                   "of a modified DADS BEAM; the real sequence's postures are not printed, ours (designed after Fig. "
                   "3.13's frames) miss the bar by 5.8 cm; the shipped sequence is our GA's (10 generations, "
                   "population 105, evolved with the cam change), which grasps with the stiff and cam-changed trunks "
                   "and misses with the soft one",
    ),
    Row(
        key="003:fig5.24",
        where="seed 003 §5.7.4, Fig. 5.24",
        what="internal force at the trunk root during the brachiation, stiff against soft trunk (simulation)",
        result="§5.7.4: '硬い場合の方がピークの値が大きいことがわかる'; the magnitude depends on modelling accuracy "
               "(no number)",
        difference="the peak internal force (§5.7.4 '体幹部の根元に生じる内力') is larger stiff, 13.0 against 11.9 N "
                   "(9 %; larger stiff in 3 of 3 shipped sequences, by 2–9 %); the bending moment, a metric of ours, goes the other "
                   "way (0.49 against 0.61 N m; larger stiff in 2 of 3 sequences); with the checked sequence the soft "
                   "trunk misses the bar, and our peaks come in the swing, not at the grasp",
    ),
    Row(
        key="003:fig5.25",
        where="seed 003 §5.7.5, Figs. 5.25–5.27",
        what="GA-generated brachiation under three stiffness policies: always stiff, always soft, and the real "
             "robot's (stiff while pulling the legs back, softest from release to the next grasp)",
        result="§5.7.5: for each policy a sequence that brachiates successfully in simulation was generated by the "
               "GA (Figs. 5.25–5.27); no comparison or fitness value printed",
        difference="a successful sequence under each policy, but success is easy on our model (random adjustments "
                   "of the designed sequence grasp in the initial population); best fitness after 10 generations "
                   "2.386 / 1.948 / 2.354 (stiff / soft / cam-changed, our weights), forward 7.8–9.1 cm",
    ),
    Row(
        key="003:fig5.28",
        where="seed 003 §5.8.2, Fig. 5.28",
        what="one BVH motion-capture clip (a 3D Studio MAX sample) played on Cla, Kenta, the humanoid HRP and the "
             "small humanoid Akira through the common EusLisp model interface",
        result="§5.8.2: '腿太と Cla は脊椎を捻って、後ろに宙返りジャンプをする構えになっているが、脊椎を持たないヒュー"
               "マノイドは体を捻っていない (捻る自由度がない)' (腿太 is the seed's OCR of 腱太). Screen shots",
        difference="kinematic, as in the thesis, on a clip shintai writes (the 3D Studio MAX sample is not ours to "
                   "ship): a 54° shoulder-against-pelvis wind-up; Cla (5 joints) and Kenta (10) reach 57° (error ≤ "
                   "3.0° / 2.7°, the trunk rotation shared equally by the joints, within ±18° / ±10°); the rigid-trunk "
                   "humanoid stays at 0° by construction; our HRP2 model (seed 000, waist yaw ±45°, a later robot "
                   "than the thesis's HRP) twists up to its 45° stop. With §5.8.2's literal DOF matching "
                   "(mapping=by_joint) Kenta's 3 matched joints reach only 30°",
    ),
    Row(
        key="003:fig5.30",
        where="seed 003 §5.9.1–5.9.4, Fig. 5.30",
        what="posture database on Kenta: postures stored in muscle-length space (a new node when farther than a "
             "threshold from all), the history of visited nodes replayed as a motion; tactile teaching triggers "
             "(weak push: model-based nudge; strong push: T mode)",
        result="§5.9.2: Fig. 5.30's bottom rows replay the taught motion from the posture history ('上段の姿勢に対応す"
               "ると思われる姿勢'); the replay's time axis is not similar to the teaching's, unlike 20 ms direct "
               "teaching; §5.9.4: the A ⇒ B motion of Fig. 5.29 was not tried. Photographs, no number",
        difference="on Cla (E9's arms-down set-up), not Kenta: our Kenta spine has no validated controller set-up; "
                   "Cla has no touch sensor, so a push is felt through its tension sensors as a moment on the spine "
                   "(τ̂ = Jᵀ ΔT); the threshold (3 mm ≈ 5° whole-spine pitch), the two push levels (0.15 / 0.6 N m), "
                   "the nudge gain and the replay speed are ours (the thesis gives none); the posture-sensor split "
                   "is off by default (ours, not the thesis's: §5.9.1 uses the posture sensor; Cla's pelvis is "
                   "fixed and its accelerometers add only motion noise, up to 30°); the trigger arms only on still "
                   "tensions (ours, added after a settling transient fired a trigger with no push)",
    ),
)
