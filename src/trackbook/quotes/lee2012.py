"""Quotes of Lee, Cui, Kim, Ma, Lee and Kim (2012), the colour + HOG + IPCA particle filter.

Each original is copied from the paper's text (Korean, or the English abstract); the
translation is beside it. Section numbers are the paper's (I-VII).
"""

from __future__ import annotations

from ._quote import Quote

QUOTES = [
    Quote("lee2012.abstract_rates", "Abstract (English)",
          r"The experiments show that the accuracy performance of particle filter using combined "
          r"color and shape information associated with on-line learning (92.4 %) is more robust "
          r"than that of particle filter using only color information (71.1 %) or particle filter "
          r"using shape and color information without on-line learning (90.3 %).",
          "The experiments show that the accuracy performance of particle filter using combined "
          "color and shape information associated with on-line learning (92.4 %) is more robust "
          "than that of particle filter using only color information (71.1 %) or particle filter "
          "using shape and color information without on-line learning (90.3 %)."),
    Quote("lee2012.abstract_problems", "Abstract (English)",
          r"Mobile robots with a side-view camera have problems as camera jitter, illumination "
          r"change, object shape variation and occlusion in variety environments.",
          "Mobile robots with a side-view camera have problems as camera jitter, illumination "
          "change, object shape variation and occlusion in variety environments."),
    Quote("lee2012.independent_motion", "§II, first paragraph",
          r"측면 카메라를 이용한 이동 로봇에서의 물체 추적은 이동 로봇의 움직임과 물체의 움직임이 "
          r"독립적이며, 추적하는 물체는 그 형태를 지속적으로 유지하지 않는다.",
          "In object tracking on a mobile robot with a side camera, the motion of the mobile "
          "robot and the motion of the object are independent, and the tracked object does not "
          "keep its shape."),
    Quote("lee2012.resize16x24", "§II, paragraph after Fig. 1",
          r"입력된 영상에서 추적하고자 하는 물체의 ROI를 선택하고, ROI의 영역을 16x24의 영상으로 "
          r"크기를 재설정 한 후,",
          "The ROI of the object to be tracked is selected in the input image, and after the ROI "
          "region is resized to a 16x24 image,"),
    Quote("lee2012.init_whole_frame", "§II, paragraph after Fig. 1",
          r"초기화를 통해 영상 전체에 분포된 파티클 영역에서 HOG 서술자와 색상 히스토그램을 각각 "
          r"계산하고,",
          "In the particle regions spread over the whole image by the initialisation, the HOG "
          "descriptor and the colour histogram are computed,"),
    Quote("lee2012.remove_old", "§II, last paragraph",
          r"이후 T 프레임 이전의 계산과 같이 파티클들의 가중 합을 통해 물체의 위치를 계산하며, 이 "
          r"위치에서의 색상과 형태 특징을 누적함과 동시에 오래된 특징을 제거한다.",
          "Then, as in the computation before frame T, the object's position is computed as the "
          "weighted sum of the particles, and the colour and shape features at this position "
          "are accumulated while, at the same time, old features are removed."),
    Quote("lee2012.t40", "§II, last sentence",
          r"제안된 알고리즘의 T는 40으로 정의하였다.",
          "T of the proposed algorithm is defined as 40."),
    Quote("lee2012.ipca_after_t", "§II, last paragraph",
          r"T 프레임 이후부터는 누적된 형태와 색상 특징을 실시간 학습 방법 중 하나인 IPCA를 "
          r"이용하여 대표적인 성분을 계산한다[15,16].",
          "From frame T on, the representative components of the accumulated shape and colour "
          "features are computed with IPCA, one of the on-line learning methods [15,16]."),
    Quote("lee2012.kernel_eq1", "§III.1, eq. 1",
          r"$$k(\|x_i^*\|^2) = 1 - r^2$$",
          "k(‖x_i*‖²) = 1 − r²"),
    Quote("lee2012.eq1_counts", "§III.1, eq. 1 and the sentence after it",
          r"$$q_u = \sum_{i=1}^n k(\|x_i^*\|^2) \delta[c(x_i) - u] \quad (1)$$ "
          r"$$k(\|x_i^*\|^2) = 1 - r^2$$ $q_u$ 는 히스토그램에서 나타내는 각 저장소에 누적된 "
          r"색상의 개수를 의미하며",
          "q_u = Σ_{i=1..n} k(‖x_i*‖²) δ[c(x_i) − u] (1), k(‖x_i*‖²) = 1 − r². q_u means the "
          "number of colours accumulated in each bin of the histogram,"),
    Quote("lee2012.kernel_radius", "§III.1, after eq. 1",
          r"$k(\|x_i^*\|^2)$ 는 물체를 표현한 ROI내 중심 픽셀에서 가장 먼 픽셀까지의 거리를 1로 "
          r"정규화한 값에서 계산하고자 하는 픽셀 $x_i^*$ 와 중심 픽셀간의 정규화된 거리를 뺀 값을 "
          r"나타낸다.",
          "k(‖x_i*‖²) is the value obtained from the distance from the centre pixel of the ROI "
          "to the farthest pixel, normalised to 1, minus the normalised distance between the "
          "pixel x_i* being computed and the centre pixel.", kind="reading"),
    Quote("lee2012.hsv_bins", "§III.1, paragraph after Fig. 4",
          r"원은 8x8x4를 이용하였다. 이동 로봇의 환경에서는 조명의 변화가 빈번히 발생할 수 "
          r"있으므로 차원을 적게 하여 조명의 변화에 민감하지 않도록 구성하였다.",
          "(the dimensions of each channel) used are 8x8x4. Since illumination changes can be "
          "frequent in a mobile robot's environment, the dimension was kept small so as not to "
          "be sensitive to illumination changes."),
    Quote("lee2012.hog_gray", "§III.2, first paragraph",
          r"차원의 효율성을 위해 1채널의 그레이(gray) 영상을 이용하는 방법을 이용하였다.",
          "for the efficiency of the dimension, the method that uses the one-channel grey "
          "image was used."),
    Quote("lee2012.hog_cells_normalise", "§III.2, first paragraph (Fig. 4)",
          r"그림 4의 왼쪽 그림에서의 물체 ROI를 6x4로 중복되지 않는 격자 영역으로 분할하고, 각 "
          r"격자에서의 크기와 방향성에 따라 값을 누적하여 각각의 서술자 표현하고, 6x4의 서술자들을 "
          r"모두 정규화하여 오른쪽 결과와 같이 표현하였다.",
          "The object ROI in the left picture of Fig. 4 is divided into 6x4 non-overlapping grid "
          "regions, values are accumulated in each grid cell by magnitude and orientation to "
          "express each descriptor, and all the 6x4 descriptors are normalised and represented "
          "as in the right result.", kind="reading"),
    Quote("lee2012.hog_blur", "§III.2, step 1",
          r"1. 윈도우 크기 5x5의 가우시안 필터(Gaussian filter)를 이용한 잡음이 제거된 영상 획득",
          "1. Obtain a denoised image with a Gaussian filter of window size 5x5"),
    Quote("lee2012.hog_gradient_eq2", "§III.2, eq. 2",
          r"$$g_x(x, y) = I(x+1, y) - I(x-1, y) \quad (2)$$ "
          r"$$g_y(x, y) = I(x, y+1) - I(x, y-1)$$",
          "g_x(x, y) = I(x+1, y) − I(x−1, y) (2); g_y(x, y) = I(x, y+1) − I(x, y−1)"),
    Quote("lee2012.hog_angle_eq3", "§III.2, step 3 (eq. 3)",
          r"$$\theta(x, y) = \tan^{-1} \left( \frac{g_y(x, y)}{g_x(x, y)} \right)$$",
          "θ(x, y) = tan⁻¹(g_y(x, y) / g_x(x, y)) (eq. 3, second line)"),
    Quote("lee2012.hog_signed_eq4", "§III.2, step 4 (eq. 4)",
          r"4. 방향성 성분을 0~360도로 만들기 위해 방향성이 0보다 작을 경우 $2\pi$ 를 더하여 계산",
          "4. To bring the orientation to 0–360 degrees, add 2π when the orientation is below 0"),
    Quote("lee2012.hog_cell_eq5", "§III.2, step 5 (eq. 5)",
          r"5. 4x4 격자(grid) 안에서 8개의 방향성 저장소 $u$ 로 누적과 정규화(normalization)을 "
          r"이용한 서술자(descriptor) 형성",
          "5. Form the descriptor by accumulation into 8 orientation bins u within a 4x4 grid "
          "and normalisation (the 4x4 grid read as a cell of 4 x 4 pixels: the 16 x 24 patch "
          "then holds the 6 x 4 cells of Fig. 4)", kind="reading"),
    Quote("lee2012.hog_eq5", "§III.2, step 5 (eq. 5)",
          r"$$D_u = \frac{1}{f} \sum_{i=1}^n m_i(x, y) \delta(\tilde{\theta}_i(x, y) - u), "
          r"\quad u = 1, \dots, 8 \quad (5)$$",
          "D_u = (1/f) Σ_{i=1..n} m_i(x, y) δ(θ̃_i(x, y) − u), u = 1, …, 8 (5); f is not "
          "defined in the text"),
    Quote("lee2012.window40", "§IV, paragraph before Fig. 5",
          r"IPCA에서 사용되는 $d \times n$ 의 행렬 $A = \{I_1, \dots, I_n\}$ 는 매 프레임 영상에서 "
          r"계산된 물체의 특징인 각 열의 $d$ 차원 벡터 $I_i$ 로 구성된다. 제안된 알고리즘에서는 "
          r"색상 히스토그램과 HOG 서술자 모두 $n = 40$ 으로 정의하였고, 각 특징의 차원을 $d$ 로 "
          r"정의하였다.",
          "The d × n matrix A = {I_1, …, I_n} used in IPCA consists of columns I_i, the "
          "d-dimensional feature vectors of the object computed in each frame. In the proposed "
          "algorithm n = 40 for both the colour histogram and the HOG descriptor, and the "
          "dimension of each feature is d."),
    Quote("lee2012.m1", "§IV, paragraph before Fig. 5",
          r"$B$ 는 $A$ 이후의 프레임에서 관측된 물체의 특징들로 만든 $d \times m$ 행렬이다. "
          r"제안된 알고리즘에서의 $m = 1$ 로 정의하였다.",
          "B is the d × m matrix made of the object's features observed in the frames after A. "
          "In the proposed algorithm m = 1."),
    Quote("lee2012.sir_condensation", "§V, first paragraph",
          r"본 논문에서는 SIR (Sequential Importance Resampling) 방법의 condensation 알고리즘을 "
          r"사용하였다[11].",
          "This paper uses the condensation algorithm, of the SIR (Sequential Importance "
          "Resampling) kind [11]."),
    Quote("lee2012.state_eq8", "§V, eq. 8",
          r"$$X = [x, y, w, h, \dot{x}, \dot{y}]^T \quad (8)$$",
          "X = [x, y, w, h, ẋ, ẏ]ᵀ (8)"),
    Quote("lee2012.motion_noise", "§V, paragraph after eq. 9",
          r"잡음을 발생시키기 위해 $\gamma_{width}$ 와 $\gamma_{height}$ 는 -2.5~2.5의 "
          r"균등분포(uniform distribution) 난수를 사용하였으며, $\gamma_{\dot{x}}$ 와 "
          r"$\gamma_{\dot{y}}$ 는 각각 -6.5~6.5, -2.5~2.5의 범위를 가지는 균등분포 난수를 "
          r"사용하였다.",
          "To generate the noise, γ_width and γ_height are uniformly distributed random numbers "
          "in −2.5 to 2.5, and γ_ẋ and γ_ẏ are uniformly distributed random numbers in the "
          "ranges −6.5 to 6.5 and −2.5 to 2.5 respectively."),
    Quote("lee2012.likelihood_eq10", "§V, eq. 10",
          r"$$p(z|x)_{color} = \frac{1}{\sqrt{2\pi\sigma_{color}^2}} "
          r"\exp\left(-\frac{1-D^2(h_x^{color}, h_{ref}^{color})}{2\sigma_{color}^2}\right) "
          r"\quad (10)$$",
          "p(z|x)_color = 1/√(2πσ²_color) · exp(−(1 − D²(h_x, h_ref)) / (2σ²_color)) (10), as "
          "printed"),
    Quote("lee2012.bhattacharyya_eq10", "§V, eq. 10",
          r"$$\text{where, } D(h_x^{color}, h_{ref}^{color}) = \sqrt{1 - \sum_{i=1}^N "
          r"\sqrt{h_{x,i}^{color} h_{ref,i}^{color}}}$$",
          "where D(h_x, h_ref) = √(1 − Σ_i √(h_x,i · h_ref,i))"),
    Quote("lee2012.likelihood_eq12", "§V, eq. 12",
          r"\exp\left(-\frac{D(z_x^{color}, z_{reconst}^{color})}{2\sigma_{color}^2}\right)$$ "
          r"$$\text{where, } z_{reconst}^{color} = U_{color} U_{color}^T z_x^{color}, \quad (12)$$ "
          r"$$D(z_x^{color}, z_{reconst}^{color}) = \sqrt{\sum_{i=1}^N z_{x,i}^{color} - "
          r"z_{reconst,i}^{color}}$$",
          "exp(−D(z_x, z_reconst) / (2σ²_color)), where z_reconst = U Uᵀ z_x (12), "
          "D(z_x, z_reconst) = √(Σ_i z_x,i − z_reconst,i) — as printed (the square of the "
          "difference is missing; D, not D², in the exponent)"),
    Quote("lee2012.sigma04", "§V, after eq. 12–13",
          r"또한 likelihood를 계산하기 위해 사용된 모든 $\sigma_{color}$ 와 $\sigma_{hog}$ 는 "
          r"0.4로 정의하였다.",
          "Also, every σ_color and σ_hog used to compute the likelihood is defined as 0.4."),
    Quote("lee2012.fusion_eq14", "§V, eq. 14",
          r"$$p(z|x) = \alpha p(z|x)_{color} + (1-\alpha) p(z|x)_{hog} \quad (14)$$",
          "p(z|x) = α p(z|x)_color + (1 − α) p(z|x)_hog (14)"),
    Quote("lee2012.alpha01", "§V, after eq. 14",
          r"본 논문에서는 실험적 결과로 $\alpha = 0.1$ 로 하여 알고리즘을 실험하였다. 이러한 "
          r"이유는 빈번하게 발생하는 조명 변화로 인해 색상 히스토그램의 정보가 HOG 서술자에 비해 "
          r"상대적으로 낮은 확신 도를 가지고 있기 때문이다.",
          "In this paper, from experimental results, the algorithm was run with α = 0.1. The "
          "reason is that, because of frequent illumination changes, the colour histogram's "
          "information has relatively low confidence compared with the HOG descriptor."),
    Quote("lee2012.init_uniform", "§V, pseudocode, t = 0",
          r"초기화: 균등하고 독립적인 난수 발생을 통해 $N$ 개의 파티클 "
          r"$x_0^{(i)}, i = [1, \dots, N]$ 을 분포시키고,",
          "Initialisation: spread N particles x_0^(i), i = 1…N, by generating uniform, "
          "independent random numbers,"),
    Quote("lee2012.resample_cumulative", "§V, pseudocode, selection step",
          r"1. 균일 분포의 난수 $r \in [0, 1]$ 생성하기 2. $c_{t-1}^{(i)} \geq r$ 인 가장 작은 "
          r"$i$ 찾기",
          "1. Generate a uniform random number r ∈ [0, 1]. 2. Find the smallest i with "
          "c_(t−1)^(i) ≥ r."),
    Quote("lee2012.pseudocode_predict", "§V, pseudocode (ELSE branch)",
          r"새로운 파티클 $x_t^{(i)} = Ax_{t-1}^{(i)} + Bz_t$ 예측하기",
          "predict the new particle x_t^(i) = A x_{t-1}^(i) + B z_t"),
    Quote("lee2012.pseudocode_weight", "§V, pseudocode (ELSE branch)",
          r"$w_t^{(i)} = p(z_t | x_{t-1}^{(i)}) = \alpha w_{t-1}^{(i),color} + "
          r"(1-\alpha)w_{t-1}^{(i),hog}$",
          "w_t^(i) = p(z_t | x_{t-1}^(i)) = α w_{t-1}^(i),color + (1 − α) w_{t-1}^(i),hog"),
    Quote("lee2012.n100", "§V, after the pseudocode",
          r"$N$ 은 파티클의 개수를 의미하며, $N=100$ 을 사용하였다.",
          "N is the number of particles; N = 100 was used."),
    Quote("lee2012.estimate_weighted_sum", "§V, after the pseudocode",
          r"$x_t$ 의 기대 값은 각 파티클의 상태변수 $x_t$ 의 가중치 $w_t$ 에 따른 가중 합을 "
          r"나타내며, 이는 추적하고 있는 물체의 위치와 크기를 나타내는 것과 같다.",
          "The expected value of x_t is the sum of the particles' state variables x_t weighted "
          "by their weights w_t, which gives the position and size of the tracked object."),
    Quote("lee2012.hardware", "§VI, Table 1",
          r"CPU / RAM Intel® Core™2 Quad CPU Q6600 2.4GHz / 4GB Tool Visual Studio 2008 / "
          r"OpenCV 2.1",
          "CPU / RAM: Intel Core 2 Quad CPU Q6600 2.4 GHz / 4 GB. Tool: Visual Studio 2008 / "
          "OpenCV 2.1"),
    Quote("lee2012.camera_resolution", "§VI, Table 1",
          r"Camera Microsoft Lifecam Cinema Image resolution 640×480 Image fps 30 fps",
          "Camera: Microsoft Lifecam Cinema. Image resolution: 640×480. Image fps: 30 fps"),
    Quote("lee2012.eight_dbs", "§VI, first paragraph",
          r"표 1은 실험이 수행된 환경을 나타내며, 표 2는 실험에 사용된 대표적인 8개의 DB를 분류를 "
          r"나타낸다.",
          "Table 1 shows the environment of the experiments, and Table 2 the classification of "
          "the 8 representative DBs used in the experiments."),
    Quote("lee2012.rapid_illumination", "§VI, paragraph after Fig. 7",
          r"실험은 표 1과 표 2의 환경에서 수행되었으며, 8개의 DB는 동일한 시나리오로 "
          r"획득하였다. 표 2의 급격한 조명 변화는 물체가 이동하는 동안 환경에서의 조명 변화가 "
          r"존재하는지의 여부를 나타내며,",
          "The experiments were run in the environments of Tables 1 and 2, and the 8 DBs were "
          "acquired with the same scenario. 'Rapid illumination change' in Table 2 says whether "
          "there is an illumination change in the environment while the object moves,"),
    Quote("lee2012.baselines", "§VI, paragraph after Fig. 7",
          r"제안된 알고리즘은 성능을 평가하기 위해 색상 히스토그램만을 이용한 파티클 필터, 색상 "
          r"히스토그램과 HOG 서술자를 혼합한 특징을 이용한 파티클 필터와 각각 비교하였다[14,20].",
          "To evaluate its performance, the proposed algorithm was compared with a particle "
          "filter using only the colour histogram and with a particle filter using the combined "
          "colour histogram and HOG descriptor features [14,20]."),
    Quote("lee2012.frame_pos", "§VI, paragraph before Table 3",
          r"또한 Frame Pos는 각 DB에서 추적에 성공한 총 프레임 수를 나타낸다.",
          "Also, Frame Pos is the total number of frames in each DB in which tracking "
          "succeeded."),
    Quote("lee2012.unfiltered_accumulation", "§VI, paragraph before Table 3",
          r"하지만 추적되는 물체의 특징을 여과 없이 누적하는 과정에서 몇 개의 DB에서는 색상 "
          r"히스토그램과 HOG 서술자를 혼합한 알고리즘보다 다소 낮은 성능을 보였다.",
          "However, because the tracked object's features are accumulated without filtering, "
          "on a few DBs it performed somewhat worse than the algorithm combining the colour "
          "histogram and the HOG descriptor."),
    Quote("lee2012.night", "§VI, paragraph before Table 3",
          r"또한, 밤에 획득된 DB에서는 충분하지 않는 조명의 효과로 인해 모든 알고리즘에서 "
          r"평균적으로 낮은 성능을 보였다.",
          "Also, on the DBs acquired at night, every algorithm performed lower on average "
          "because of insufficient lighting."),
    Quote("lee2012.table3_header", "§VI, Table 3, header",
          r"Name Total Frame Color [20] Color + HOG [14] Proposed",
          "Name, Total Frame, Color [20], Color + HOG [14], Proposed"),
    Quote("lee2012.table3_db01", "§VI, Table 3, first row",
          r"DB 01 3015 2128 70.6 2883 95.6 2923 96.9",
          "DB 01: Total Frame 3015; Color: Frame Pos 2128, 70.6 %; Color + HOG: 2883, 95.6 %; "
          "Proposed: 2923, 96.9 %"),
    Quote("lee2012.table3_rows", "§VI, Table 3, the eight rows",
          r"DB 01 3015 2128 70.6 2883 95.6 2923 96.9 DB 02 2790 2361 84.6 2555 91.6 2689 96.4 "
          r"DB 03 3545 2413 68.1 3397 95.8 3365 94.9 DB 04 3215 2198 68.4 3035 94.4 3052 94.9 "
          r"DB 05 774 501 64.7 628 81.1 658 85.0 DB 06 1360 731 53.8 957 70.4 922 67.8 "
          r"DB 07 1129 735 65.1 861 76.3 1014 89.8 DB 08 1347 1147 85.2 1187 88.1 1253 93.0",
          "Total Frame, then Frame Pos and % for Color, Color + HOG and Proposed, per DB: "
          "DB 01 3015: 2128 70.6, 2883 95.6, 2923 96.9; DB 02 2790: 2361 84.6, 2555 91.6, "
          "2689 96.4; DB 03 3545: 2413 68.1, 3397 95.8, 3365 94.9; DB 04 3215: 2198 68.4, "
          "3035 94.4, 3052 94.9; DB 05 774: 501 64.7, 628 81.1, 658 85.0; DB 06 1360: 731 53.8, "
          "957 70.4, 922 67.8; DB 07 1129: 735 65.1, 861 76.3, 1014 89.8; DB 08 1347: "
          "1147 85.2, 1187 88.1, 1253 93.0"),
    Quote("lee2012.table3_average", "§VI, Table 3, last rows",
          r"Average 71.1 % 90.3 % 92.4 % Processing Time 7 ms 13 ms 55 ms",
          "Average: Color 71.1 %, Color + HOG 90.3 %, Proposed 92.4 %. Processing Time: 7 ms, "
          "13 ms, 55 ms"),
    Quote("lee2012.failed_for_a_while", "§VII, second paragraph",
          r"하지만 실험 결과에서 보이는 것과 같이 물체의 특징이 기존의 특징과 유사성을 지니는지의 "
          r"판별을 하지 않고 누적한 결과로 인해 추적이 잠시 동안 실패함에 따라 성능이 저하됨을 "
          r"보였다.",
          "However, as the experimental results show, because the object's features were "
          "accumulated without judging whether they resemble the existing features, tracking "
          "failed for a while and the performance dropped."),
    Quote("lee2012.accumulate_every_frame", "§VII, first paragraph",
          r"또한, 추적되는 물체의 정보를 매 프레임 동안 누적하고 실시간 학습을 통해 주요 성분을 "
          r"분석하고",
          "Also, the tracked object's information is accumulated every frame and its principal "
          "components are analysed by on-line learning"),
    Quote("lee2012.hog_robust_light", "§I, fourth paragraph",
          r"영상 내에서 물체의 형태를 표현하기에 적합하며, 조명의 변화에 강인한 성질을 나타내어 많은 "
          r"물체 추적 응용에서 사용되고 있다.",
          "(HOG) is suited to representing the shape of an object in an image and is robust to "
          "illumination changes, so it is used in many object tracking applications."),
    Quote("lee2012.resize_reason", "§II, paragraph after Fig. 1",
          r"영상의 크기를 재설정하는 이유는 물체의 특징의 차원을 줄이고, 주요 특징 성분만 계산하기 "
          r"위함이다.",
          "The reason for resizing the image is to reduce the dimension of the object's features "
          "and to compute only the main feature components."),
    Quote("lee2012.hsv_channels", "§III.1, last paragraph",
          r"따라서 HSV모델에서 색상(hue), 채도(saturation), 밝기(value)를 모두 이용하도록 "
          r"구성하였으며,",
          "Therefore it was built to use all of hue, saturation and value of the HSV model,"),
    Quote("lee2012.hsv_fig3", "§III.1, Fig. 3 caption",
          r"Fig. 3. 3D color histogram in HSV (8x8x4) in HSV model.",
          "Fig. 3. 3D color histogram in HSV (8x8x4) in HSV model."),
    Quote("lee2012.hog_fig4", "§III.2, Fig. 4 caption",
          r"그림 4. 8개의 방향성을 가지는 24(6x4)개의 HOG 서술자.",
          "Fig. 4. 24 (6x4) HOG descriptors with 8 orientations."),
    Quote("lee2012.processing_55ms", "§VII, last paragraph",
          r"또한 제안된 알고리즘은 평균 55 ms의 처리 속도를 가지므로 CPU기반 혹은 GPU기반의 병렬 "
          r"처리 프로그래밍을 적용한다면 보다 향상된 처리 시간을 통해 실시간 처리가 가능할 것으로 "
          r"예상된다.",
          "Also, since the proposed algorithm takes 55 ms on average, real-time processing is "
          "expected to be possible with the faster processing that CPU- or GPU-based parallel "
          "programming would bring."),
    Quote("lee2012.update_eq6", "§IV, eq. 6 and the sentence after it",
          r"$$[A \ B] = [U \ \tilde{B}] \begin{bmatrix} \Sigma & U^T B \\ 0 & B^T B \end{bmatrix} "
          r"\begin{bmatrix} V^T & 0 \\ 0 & I \end{bmatrix} \quad (6)$$ "
          r"여기서 $\tilde{B}$ 는 $U$ 에 직교인 $B$ 의 요소를 나타내며,",
          "[A B] = [U B̃] [[Σ, UᵀB], [0, BᵀB]] [[Vᵀ, 0], [0, I]] (6), as printed; where B̃ "
          "denotes the component of B orthogonal to U,"),

]
