"""Quotes of Cho and Kang (2005), Condensation with mean-shift moved candidates.

Each original is copied from the paper's text (Korean, or the English abstract); the
translation is beside it. Section numbers are the paper's (1-6).
"""

from __future__ import annotations

from ._quote import Quote

QUOTES = [
    Quote("cho2005.abstract_few_hypotheses", "Abstract (English)",
          r"Although it uses only a few hypotheses, the proposed method use a high-likelihood "
          r"hypotheses using mean-shift algorithm.",
          "Although it uses only a few hypotheses, the proposed method use a high-likelihood "
          "hypotheses using mean-shift algorithm."),
    Quote("cho2005.mean_shift_fails_overlap", "§1, paragraph on mean-shift",
          r"하지만 지역 모드로 수렴하는 특성으로 인해 객체 사이의 겹침과 같은 상황에서는 추적이 "
          r"실패하게 된다.",
          "However, because it converges to a local mode, tracking fails in situations such as "
          "overlap between objects."),
    Quote("cho2005.ellipse", "§3.1, first sentence",
          r"본 논문에서 객체는 타원으로 정의한다.",
          "In this paper an object is defined as an ellipse."),
    Quote("cho2005.state_eq1", "§3.1, eq. 1",
          r"$$\mathbf{x} = \{x, y, \dot{x}, \dot{y}, H_x, H_y, a\} \quad (1)$$",
          "x = {x, y, ẋ, ẏ, H_x, H_y, a} (1)"),
    Quote("cho2005.state_meaning", "§3.1, after eq. 1",
          r"여기서 x, y 는 타원의 중심, \dot{x}, \dot{y} 는 모션(motion), H_x, H_y 는 각각 타원의 "
          r"장축과 단축의 길이의 절반, a 는 크기의 변",
          "where x, y is the centre of the ellipse, ẋ, ẏ the motion, H_x, H_y half the lengths "
          "of the major and minor axes, and a the change of size"),
    Quote("cho2005.kernel_eq2", "§3.1, eq. 2",
          r"$$k(r) = \begin{cases} 1 - r^2 & r < 1 \\ 0 & \text{otherwise} \end{cases} "
          r"\quad (2)$$",
          "k(r) = 1 − r² for r < 1, 0 otherwise (2)"),
    Quote("cho2005.colour_eq3", "§3.1, eq. 3",
          r"$$p_y = f \sum_{i=1}^I k\left(\frac{\|\mathbf{y} - \mathbf{x}_i\|}{a}\right) "
          r"\delta[h(\mathbf{x}_i) - u] \quad (3)$$",
          "p_y = f Σ_i k(‖y − x_i‖ / a) δ[h(x_i) − u], i = 1…I (3)"),
    Quote("cho2005.bandwidth_eq3", "§3.1, after eq. 3",
          r"여기서, k 는 커널 프로파일 함수(kernel profile function), I 는 타원 안의 pixel의 수, "
          r"δ 는 Kronecker delta 함수, a 는 $\sqrt{H_x^2 + H_y^2}$, f 는 normalization factor이다.",
          "where k is the kernel profile function, I the number of pixels inside the ellipse, δ "
          "the Kronecker delta function, a is √(H_x² + H_y²), and f a normalisation factor."),
    Quote("cho2005.factored_sampling", "§3.2, first sentence",
          r"Condensation(Bayesian Filter, Monte Carlo Method, Particle filter) 알고리즘은 "
          r"Factored Sampling에 기반한 확률적인 객체 추적 알고리즘이다[1-2].",
          "The Condensation (Bayesian filter, Monte Carlo method, particle filter) algorithm is "
          "a probabilistic object tracking algorithm based on factored sampling [1-2]."),
    Quote("cho2005.condensation_sampling", "§3.2, step ①",
          r"① 샘플링(Sampling) 이전 단계의 Conditional Observation 확률 "
          r"$p(\mathbf{x}_{t-1} | \mathbf{z}_{t-1})$ 을 이용해서 후보 집합 "
          r"$(\mathbf{s}_{t-1}, \pi_{t-1})$ 로부터 샘플링해서 새로운 후보 집합 S'_{t-1} 을 얻는다.",
          "① Sampling: using the previous step's conditional observation probability "
          "p(x_(t−1) | z_(t−1)), sample from the candidate set (s_(t−1), π_(t−1)) to obtain a "
          "new candidate set S′_(t−1).", kind="reading"),
    Quote("cho2005.condensation_recovers", "§3.2, last paragraph",
          r"Condensation 알고리즘은 복수개의 후보를 이용하기 때문에 복잡한 배경에서 추적이 "
          r"용이하고, 또한 일시적인 오류가 발생하더라도 복구가 가능한 장점이 있는 반면, 계산 "
          r"복잡도가 높아지는 단점이 있다.",
          "Because the Condensation algorithm uses several candidates, it tracks easily in a "
          "cluttered background and can recover even when a temporary error occurs, but its "
          "computational complexity is high."),
    Quote("cho2005.condensation_measurement", "§3.2, step ③",
          r"③ 측정(Measurement) 모든 후보에 대해서 다음을 계산한다. "
          r"$$\pi_t^i = p(\mathbf{z}_t | \mathbf{x}_t = \mathbf{s}_t^i)$$",
          "③ Measurement: for every candidate, compute π_t^i = p(z_t | x_t = s_t^i) (no "
          "likelihood function is printed)"),
    Quote("cho2005.fig1_estimate", "§4.1, caption of Fig. 1",
          r"(그림 1) 객체 후보들의 유사도, 회색 점들은 각 후보들의 위치와 그 유사도를 나타내고, "
          r"검은색 점은 후보들에 의해 추정된 위치와 유사도를 나타낸다.",
          "Fig. 1: the likelihood of the object candidates; the grey dots show each candidate's "
          "position and likelihood, and the black dot the position estimated from the "
          "candidates and its likelihood (how it is estimated is not printed)."),
    Quote("cho2005.mean_shift_weights", "§3.3, step ②",
          r"② $w_i = \sum_{u=1}^m \sqrt{\frac{\hat{q}_u}{\hat{p}_u(\hat{\mathbf{y}}_0)}} "
          r"\delta[h(\mathbf{x}_i) - u]$ 을 계산한다.",
          "② Compute w_i = Σ_u √(q̂_u / p̂_u(ŷ_0)) δ[h(x_i) − u]."),
    Quote("cho2005.mean_shift_step3", "§3.3, step ③",
          r"$$\hat{\mathbf{y}}_1 = \frac{\sum_{i=1}^{n_h} \mathbf{x}_i w_i "
          r"g\left(\frac{\|\hat{\mathbf{y}}_0 - \mathbf{x}_i\|^2}{h}\right)}{\sum_{i=1}^{n_h} "
          r"w_i g\left(\frac{\|\hat{\mathbf{y}}_0 - \mathbf{x}_i\|^2}{h}\right)}$$",
          "ŷ_1 = Σ_i x_i w_i g(‖ŷ_0 − x_i‖² / h) / Σ_i w_i g(‖ŷ_0 − x_i‖² / h), i = 1…n_h — "
          "as printed: the squared distance divided by h, not by h²"),
    Quote("cho2005.g_is_minus_k_prime", "§3.3, step ③",
          r"(여기서, $g = -k'$)",
          "(where g = −k′)"),
    Quote("cho2005.mean_shift_halving", "§3.3, step ⑤",
          r"⑤ $\rho[\hat{\mathbf{p}}(\hat{\mathbf{y}}_1), \hat{\mathbf{q}}] < "
          r"\rho[\hat{\mathbf{p}}(\hat{\mathbf{y}}_0), \hat{\mathbf{q}}]$ 이면, "
          r"$\hat{\mathbf{y}}_1 \leftarrow \frac{1}{2}(\hat{\mathbf{y}}_0 + \hat{\mathbf{y}}_1)$ "
          r"로 세팅한 뒤",
          "⑤ If ρ[p̂(ŷ_1), q̂] < ρ[p̂(ŷ_0), q̂], set ŷ_1 ← ½(ŷ_0 + ŷ_1) and then"),
    Quote("cho2005.mean_shift_stop", "§3.3, step ⑥",
          r"⑥ 만약 $\|\hat{y}_1 - \hat{y}_0\| < \varepsilon$ 이면 그만하고, 아니면 "
          r"$\hat{y}_0 \leftarrow \hat{y}_1$ 으로 세팅하고 2번째 단계로 간다.",
          "⑥ If ‖ŷ_1 − ŷ_0‖ < ε, stop; otherwise set ŷ_0 ← ŷ_1 and go to the 2nd step."),
    Quote("cho2005.mean_shift_local_mode", "§3.3, last paragraph",
          r"Mean-shift 알고리즘은 단일 후보를 이용하기 때문에 요구되는 계산 복잡도는 낮은 반면에, "
          r"주변의 지역 모드 위치로 수렴하게 되는 단점을 가지고 있다. 따라서, 겹침이 있거나 배경이 "
          r"복잡한 환경에서는 좋은 성능을 발휘하지 못하게 된다.",
          "Because the mean-shift algorithm uses a single candidate, its computational "
          "complexity is low, but it has the drawback of converging to a nearby local mode. It "
          "therefore does not perform well where there is overlap or a cluttered background."),
    Quote("cho2005.move_candidates", "§4, first paragraph",
          r"이를 위해, 본 논문에서는 후보들의 유사도를 높이기 위해 그레이디언트 방향과 동일한 "
          r"방향을 가지는 Mean-shift 벡터 방향으로 후보의 위치를 바꿔주는 방법을 이용한다.",
          "To this end, this paper raises the candidates' likelihood by moving each candidate's "
          "position along the mean-shift vector, which points in the gradient direction."),
    Quote("cho2005.low_likelihood_waste", "§4.1, after Fig. 1",
          r"이러한 낮은 유사도를 가지는 후보들은 추정단계(estimation step)에서 객체 위치를 "
          r"추정하는데 기여도가 낮기 때문에, 이러한 후보들이 많이 생성될수록 시스템의 효율성은 "
          r"떨어지게 된다.",
          "Because such low-likelihood candidates contribute little to estimating the object's "
          "position in the estimation step, the more of them are generated, the less efficient "
          "the system becomes."),
    Quote("cho2005.motion_vector", "§4.2, before eq. 5",
          r"이러한 후보의 생성 문제를 해결하기 위해 본 논문에서는 객체의 모션 벡터(Motion "
          r"vector)를 이용한다.",
          "To solve this problem of generating candidates, this paper uses the object's motion "
          "vector."),
    Quote("cho2005.flow_eq7", "§4.2, eq. 7",
          r"$$pI_x + qI_y + I_t = 0 \quad (7)$$",
          "p I_x + q I_y + I_t = 0 (7)"),
    Quote("cho2005.flow_eq8", "§4.2, eq. 8",
          r"$$Err^{(t)}(p, q) = \sum_{(x, y) \in R} (pI_x + qI_y + I_t)^2 \quad (8)$$",
          "Err^(t)(p, q) = Σ_(x, y) ∈ R (p I_x + q I_y + I_t)² (8)"),
    Quote("cho2005.candidates_eq9", "§4.2, eq. 9",
          r"$$\mathbf{s}_t = A\mathbf{s}_{t-1} + \mathbf{w}_{t-1} \quad (9)$$ 여기서, A 는 model의 "
          r"deterministic component이고, \mathbf{w}_{t-1} 은 multivariate random variable이다.",
          "s_t = A s_(t−1) + w_(t−1) (9), where A is the deterministic component of the model "
          "and w_(t−1) a multivariate random variable."),
    Quote("cho2005.bandwidth_eq10", "§4.2, after eq. 10",
          r"여기서, n 은 후보 인덱스(Sample Index), I 는 타원 안의 pixel의 수, δ 는 Kronecker "
          r"delta 함수, a 는 $\sqrt{H_x^2 + H_y^2}$, f 는 normalization factor이다.",
          "where n is the candidate (sample) index, I the number of pixels inside the ellipse, "
          "δ the Kronecker delta function, a is √(H_x² + H_y²), and f a normalisation factor."),
    Quote("cho2005.mean_shift_eq12", "§4.2, eq. 12",
          r"$$\mathbf{y}^n = \frac{\sum_{i=1}^n \mathbf{x}_i^n w_i^n g \left(\frac{\|\mathbf{y}_0^n "
          r"- \mathbf{x}_i^n\|^2}{a} \right)}{\sum_{i=1}^n w_i^n g \left(\frac{\|\mathbf{y}_0^n - "
          r"\mathbf{x}_i^n\|^2}{a} \right)} - \mathbf{y}_0^n \quad (12)$$",
          "y^n = Σ_i x_i^n w_i^n g(‖y_0^n − x_i^n‖² / a) / Σ_i w_i^n g(‖y_0^n − x_i^n‖² / a) "
          "− y_0^n (12): the mean-shift vector of candidate n, with the bandwidth a of eq. 10"),
    Quote("cho2005.likelihood_rises_eq13", "§4.2, eq. 13",
          r"$$\rho[\mathbf{p}(\mathbf{y}_0^n), \mathbf{q}] \leq \rho[\mathbf{p}(\mathbf{y}_1^n), "
          r"\mathbf{q}] \quad \text{where } \mathbf{y}_1^n = \mathbf{y}_0^n + \mathbf{y}^n "
          r"\quad (13)$$",
          "ρ[p(y_0^n), q] ≤ ρ[p(y_1^n), q], where y_1^n = y_0^n + y^n (13)"),
    Quote("cho2005.hardware", "§5.1, first paragraph",
          r"본 실험은 CPU P4-1.5GHz와 메모리 512MB의 성능을 가지는 PC에서 수행했다. OS는 "
          r"Microsoft사의 Windows XP를 이용했고, 개발 툴은 Microsoft Visual C++와 Intel사의 "
          r"IPL(Image Processing Library), OpenCV(Open Computer Vision Library)를 이용했다. 모든 "
          r"시퀀스는 320×240 해상도를 가지는 비트맵 시퀀스(Bitmap Sequence)를 사용했다.",
          "The experiments ran on a PC with a P4 1.5 GHz CPU and 512 MB of memory. The OS was "
          "Microsoft Windows XP, and the development tools were Microsoft Visual C++, Intel's "
          "IPL (Image Processing Library) and OpenCV (Open Computer Vision Library). Every "
          "sequence was a bitmap sequence at 320×240 resolution."),
    Quote("cho2005.condensation_n100", "§5.1, second paragraph",
          r"본 논문에서는 Condensation 추적방법과의 비교를 위해 이와 비슷한 100개의 후보를 "
          r"이용하는 Condensation 추적 시스템을 구성했다.",
          "For the comparison with Condensation tracking, this paper built a Condensation "
          "tracking system with a similar number, 100 candidates."),
    Quote("cho2005.mean_shift_comaniciu", "§5.1, second paragraph",
          r"또한 Mean-shift를 이용한 추적 시스템을 구성하는데는 D. Comaniciu [3-5]가 제안한 "
          r"방법을 이용했다.",
          "The mean-shift tracking system was built with the method D. Comaniciu proposed "
          "[3-5]."),
    Quote("cho2005.proposed_n5", "§5.1, second paragraph",
          r"그리고 제안된 방법을 이용한 추적 시스템의 경우에는 후보 5개를 이용했다.",
          "And the tracking system of the proposed method used 5 candidates."),
    Quote("cho2005.sequences", "§5.1, third paragraph",
          r"단일 추적 실험에 쓰인 시퀀스는 사람이 계단을 오르는 시퀀스와 사람이 나무에 가려지는 "
          r"시퀀스, 그리고 사람이 책장 앞에서 움직이는 시퀀스이고, 다중 객체 추적 실험에 쓰인 "
          r"시퀀스는 두 사람의 얼굴이 겹쳐지는 시퀀스이다.",
          "The sequences of the single-tracking experiments are a person climbing stairs, a "
          "person occluded by a tree and a person moving in front of a bookcase; the sequence "
          "of the multiple-object experiment is two people's faces overlapping."),
    Quote("cho2005.table1_seconds", "§5.2, Table 1",
          r"〈표 1〉 단일 추적의 경우 프레임당 처리 시간 Condensation Mean-shift 제안된 추적기 "
          r"프레임당 처리시간 (sec) 0.084 0.007 0.035",
          "Table 1. Processing time per frame, single tracking — Condensation, Mean-shift, "
          "proposed tracker: processing time per frame (sec) 0.084, 0.007, 0.035"),
    Quote("cho2005.mean_likelihood", "§5.2, Fig. 5",
          r"(그림 5)는 (그림 4)에서 보인 단일 추적 경우의 Condensation 추적기와 제안된 추적기에서 "
          r"사용한 후보들의 평균 유사도를 나타낸 것이다.",
          "Fig. 5 shows the mean likelihood of the candidates used by the Condensation tracker "
          "and the proposed tracker in the single tracking of Fig. 4."),
    Quote("cho2005.error_curves", "§5.2, Fig. 6",
          r"(그림 6)은 각 추적기의 오차를 나타낸 것이다.",
          "Fig. 6 shows the error of each tracker."),
    Quote("cho2005.error_jump_128", "§5.2, paragraph on Fig. 6",
          r"에서 갑자기 오차가 급증하는 것을 볼 수 있다. 이것은 Mean-shift가 전역 모드(global "
          r"mode) 위치가 아닌 지역 모드(local mode) 위치로 수렴하는 특성 때문에 나타난다.",
          "(In Fig. 6 the mean-shift tracker and the proposed tracker, near frame 128,) show a "
          "sudden jump of the error. This comes from mean-shift converging to a local mode "
          "rather than to the global mode."),
    Quote("cho2005.occlusion_single", "§5.2, Fig. 7",
          r"100개의 후보를 사용하는 Condensation 추적기와 5개의 후보를 사용한 제안된 추적기의 "
          r"경우에는 비록 객체에 겹침이 발생하더라도 추적에 성공하는데 반면, 단일 후보를 이용하는 "
          r"mean-shift 추적기의 경우에는 겹침이 발생하면 추적에 실패한다.",
          "The Condensation tracker with 100 candidates and the proposed tracker with 5 "
          "candidates track successfully even when the object is occluded, whereas the "
          "mean-shift tracker, which uses a single candidate, fails when occlusion occurs."),
    Quote("cho2005.multi_tracking", "§5.3, first paragraph",
          r"(그림 9)은 Condensation 추적기, Mean-shift 추적기, 제안된 추적기의 다중 추적(Multiple "
          r"Tracking) 결과를 나타낸 것이다.",
          "Fig. 9 shows the multiple-tracking results of the Condensation tracker, the "
          "mean-shift tracker and the proposed tracker."),
    Quote("cho2005.multi_mean_shift_fails", "§5.3, first paragraph",
          r"Mean-shift 추적기의 경우 겹침이 발생 후에는 추적에 실패하게 된다. 이는 앞에서 언급한 "
          r"Mean-shift 추적기의 수렴성 때문이다.",
          "the mean-shift tracker fails to track after the overlap occurs. This is because of "
          "the convergence property of the mean-shift tracker mentioned above."),
    Quote("cho2005.table2_seconds", "§5.3, Table 2",
          r"<표 2> 다중 추적 경우 프레임 당 처리 시간 Condensation Mean-shift 제안된 추적기 "
          r"프레임당 처리시간 (sec) 0.248 0.017 0.086",
          "Table 2. Processing time per frame, multiple tracking — Condensation, Mean-shift, "
          "proposed tracker: processing time per frame (sec) 0.248, 0.017, 0.086"),
    Quote("cho2005.multi_time", "§5.3, second paragraph",
          r"단일 추적일 때와 마찬가지로 Condensation 추적기에 비해 제안된 추적기의 프레임 당 처리 "
          r"시간이 적게 소요되는 것을 확인할 수 있다.",
          "As in single tracking, the proposed tracker takes less processing time per frame "
          "than the Condensation tracker."),
    Quote("cho2005.multi_error", "§5.3, Fig. 11",
          r"(그림 11)은 다중 추적에서의 각 추적기의 오차를 나타낸 것이다. Mean-Shift 추적기의 경우 "
          r"겹침으로 인해 추적에 실패하게 되고, Condensation 추적기보다는 전반적으로 적은 오차를 "
          r"나타내고 있는 것을 확인할 수 있다.",
          "Fig. 11 shows each tracker's error in multiple tracking. The mean-shift tracker fails "
          "because of the overlap, and a smaller error overall than the Condensation tracker's "
          "can be seen (the clause names no subject: the proposed tracker, in the book's "
          "reading).", kind="reading"),
    Quote("cho2005.parameters_drawback", "§6, last paragraph",
          r"하지만 제안된 시스템의 경우, 시스템의 성능을 좌우하는 여러 파라미터들을 적절히 "
          r"바꿔줘야 하는 단점을 가지고 있다.",
          "However, the proposed system has the drawback that several parameters that govern "
          "its performance have to be adjusted appropriately."),
    Quote("cho2005.mean_shift_eq4", "§3.3, eq. 4",
          r"$$\Delta\mathbf{x} = \frac{\sum_a K(a - \mathbf{x})w(a)a}{\sum_a K(a - \mathbf{x})w(a)} "
          r"\quad (4)$$",
          "Δx = Σ_a K(a − x) w(a) a / Σ_a K(a − x) w(a) (4) — as printed: the weighted mean "
          "itself, without the subtraction of x"),
    Quote("cho2005.weights_eq11", "§4, eq. 11",
          r"$$w_i^n = \sum_{u=1}^m \sqrt{\frac{\hat{q}}{\hat{p}_n(\mathbf{y}_0)}} "
          r"\delta[h(\mathbf{x}_i^n) - u] \quad (11)$$",
          "w_i^n = Σ_u √(q̂ / p̂_n(y_0)) δ[h(x_i^n) − u] (11) — as printed: q̂ and p̂_n "
          "without the bin index u"),
]
