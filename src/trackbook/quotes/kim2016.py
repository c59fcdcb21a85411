"""Quotes of Kim, Kim and Choi (2016), the edge observation model particle filter.

Each original is copied from the paper's text (Korean, or the English abstract); the
translation is beside it. Section numbers are the paper's (1-5).
"""

from __future__ import annotations

from ._quote import Quote

QUOTES = [
    Quote("kim2016.abstract_middle_distance", "Abstract (English)",
          r"It calculates the weight by comparing the average of the middle distance in eight-way "
          r"of particle filter edge model with that in edge observation model, and then updates "
          r"the weight with the calculated value.",
          "It calculates the weight by comparing the average of the middle distance in eight-way "
          "of particle filter edge model with that in edge observation model, and then updates "
          "the weight with the calculated value."),
    Quote("kim2016.edge_model_eight_rays", "§2, paragraph after Fig. 2",
          r"본 논문에서는 초기 프레임에서 에지 영상을 생성한 후, 초기 영역에서 사용자가 지정한 "
          r"영역 중심으로부터 8방향으로 가장 가까운 에지를 탐색하여 그림 2와 같은 관측모델을 "
          r"생성하는 것을 제안한다.",
          "This paper proposes to build the edge image in the initial frame and then, from the "
          "centre of the region the user selected, to search for the nearest edge in 8 "
          "directions, which gives the observation model of Fig. 2."),
    Quote("kim2016.rays45", "§2, after eq. 1",
          r"관측 모델 M 는 사용자가 지정한 영역의 중심으로부터 45° 씩 8방향으로 가장 가까운 에지를 "
          r"탐색하여 8방향 에지 모델로 만들어진다.",
          "The observation model M is made into an 8-direction edge model by searching for the "
          "nearest edge in 8 directions, 45° apart, from the centre of the region the user "
          "selected."),
    Quote("kim2016.model_eq1", "§2, eq. 1",
          r"$$M = \{mDis_j, \theta_j\} \quad [j \in 1 \dots 8] \quad (1)$$",
          "M = {mDis_j, θ_j}, j ∈ 1…8 (1)"),
    Quote("kim2016.perspective_ratio", "§2, last paragraph",
          r"또한, 에지 관측 모델의 8방향 거리에 대한 비율을 이용하여 이동 객체의 원근에 의한 추적 "
          r"오차를 줄였다.",
          "Also, the ratio of the edge observation model's 8-direction distances is used to "
          "reduce the tracking error caused by the moving object's perspective (distance)."),
    Quote("kim2016.max999", "§3, before eq. 2",
          r"파티클의 총 개수인 N 은 사용자가 원하는 개수로 설정할 수 있고, N 이 클수록 추적에 "
          r"대한 정확도를 높일 수 있다. 본 논문에서는 최대 999개의 파티클을 사용하였다.",
          "The total number of particles N can be set to the number the user wants, and the "
          "larger N, the higher the tracking accuracy. In this paper at most 999 particles were "
          "used."),
    Quote("kim2016.state_eq3", "§3, eq. 3",
          r"상태 변수 X_t^i 는 영상에서 각 파티클의 위치 좌표를 표현하기 위한 변수 x_t^i, y_t^i "
          r"를 이용하여 식 3과 같이 나타낸다.",
          "The state variable X_t^i is written as in eq. 3 with the variables x_t^i, y_t^i that "
          "express the position coordinates of each particle in the image."),
    Quote("kim2016.init_equal_weights", "§3.1, Table 2 (algorithm), t = 0",
          r"가중치가 동일한 랜덤 파티클 N개를 생성.",
          "Generate N random particles with equal weights."),
    Quote("kim2016.resample_proportional", "§3.1, paragraph after Table 2",
          r"업데이트된 가중치에 비례하여 파티클들을 리샘플링하고, 추적 객체의 상태인 위치를 "
          r"갱신하여 현재 위치를 추정하게 된다.",
          "The particles are resampled in proportion to the updated weights, and the position, "
          "the state of the tracked object, is updated to estimate the current position."),
    Quote("kim2016.prediction_step", "§3.2, prediction step",
          r"예측 단계 (Prediction Step)는 추적하는 객체의 이동량에 따라 그 이동량만큼 파티클들을 "
          r"이동시킨다. 본 논문에서의 실험은 프레임 별 이동 변화가 작은 객체에 적용하기 때문에, "
          r"이동시킬 파티클의 이동량이 작아 실험에 영향을 주지 않는다고 가정한다.",
          "The prediction step moves the particles by the tracked object's displacement. Since "
          "the experiments of this paper apply to objects whose motion from frame to frame is "
          "small, the displacement of the particles is small and is assumed not to affect the "
          "experiments.", kind="reading"),
    Quote("kim2016.sort_middle", "§3.2, update step",
          r"먼저, 관측 모델 M 과 에지 모델 p 의 8방향 거리인 $mDis_j, pDis_j$ 를 각 거리에 대해 "
          r"길이 순으로 정렬하고, 중간 길이인 4, 5번째 거리의 평균을 이용하여 두 모델의 유사성을 "
          r"알 수 있다.",
          "First, the 8-direction distances mDis_j, pDis_j of the observation model M and of the "
          "edge model p are each sorted by length, and the similarity of the two models is "
          "found from the mean of the middle, 4th and 5th, distances."),
    Quote("kim2016.ratio_eq5", "§3.2, eq. 5",
          r"$$Ratio = \frac{pAvg}{mAvg}$$",
          "Ratio = pAvg / mAvg (eq. 5)"),
    Quote("kim2016.ratio_window", "§3.2, after eq. 5",
          r"본 논문에서는 $Ratio$ 의 범위를 0.8~1.2로 지정하였다. $Ratio$ 값이 지정 범위 밖에 "
          r"있을 경우 그 파티클의 가중치 w_t^i 는 0의 값이 된다.",
          "In this paper the range of Ratio is set to 0.8–1.2. When the value of Ratio lies "
          "outside the set range, the weight w_t^i of that particle becomes 0."),
    Quote("kim2016.weight_eq6", "§3.2, eq. 6",
          r"$$w_t^i = 1 - \left(\frac{\sum_{j=1}^k |pDis_j - mDis_j|}{\sum_{j=1}^k mDis_j} "
          r"\right) \quad (6)$$",
          "w_t^i = 1 − (Σ_j |pDis_j − mDis_j|) / (Σ_j mDis_j), j = 1…k (6)"),
    Quote("kim2016.estimate_eq7", "§3.2, eq. 7",
          r"$$C_t^x = \sum_{i=1}^N (x_t^i * w_t^i) \quad C_t^y = \sum_{i=1}^N (y_t^i * w_t^i) "
          r"\quad (7)$$",
          "C_t^x = Σ_i x_t^i · w_t^i, C_t^y = Σ_i y_t^i · w_t^i (7)"),
    Quote("kim2016.five_videos", "§4, first paragraph",
          r"본 논문에서는 에지 관측 모델을 가진 파티클 필터의 성능을 평가하기 위하여 5개의 동영상을 "
          r"실험 영상으로 사용하였다.",
          "To evaluate the particle filter with the edge observation model, this paper used 5 "
          "videos as test videos."),
    Quote("kim2016.baselines", "§4, first paragraph",
          r"(1) HSI 색상 모델 기반 파티클 필터를 이용한 방법, (2) HOG특징 기반 파티클 필터를 이용한 "
          r"방법, (3) 에지 관측 모델을 가진 파티클 필터를 이용한 방법의 성능을 비교하였다.",
          "the performance of (1) the method using a particle filter based on the HSI colour "
          "model, (2) the method using a particle filter based on HOG features and (3) the "
          "method using a particle filter with the edge observation model was compared."),
    Quote("kim2016.correct", "§4, second paragraph (Table 3)",
          r"표 3에서 Correct는 각 비디오 영상에서 객체가 추적에 성공한 프레임의 개수를 나타내고, "
          r"%는 각 비디오에 대한 객체 추적 성공률을 나타낸다.",
          "In Table 3, Correct is the number of frames of each video in which the object was "
          "tracked successfully, and % is the object-tracking success rate of each video."),
    Quote("kim2016.table3_average", "Table 3 (§4), last row",
          r"Avg 62.3 70.4 89.8",
          "Avg: HSI Color 62.3 %, HOG 70.4 %, Proposed 89.8 %"),
    Quote("kim2016.table3_video1", "Table 3 (§4), first row",
          r"Video1 603 325 53.8 412 68.3 533 88.3",
          "Video1: Total Frame 603; HSI Color: Correct 325, 53.8 %; HOG: 412, 68.3 %; "
          "Proposed: 533, 88.3 %"),
    Quote("kim2016.error_centre_distance", "§4, paragraph after Fig. 5",
          r"그림 5는 그림 4의 실험결과를 바탕으로 추적하고자 하는 객체의 실제 중심 좌표와 (1), "
          r"(2), (3) 세 가지의 방법으로 추정된 중심좌표의 거리 차를 비교하였다.",
          "Fig. 5 compares, on the experiment of Fig. 4, the distance between the true centre "
          "of the object to be tracked and the centre estimated by each of the three methods "
          "(1), (2), (3)."),
    Quote("kim2016.error_hsi60", "§4, paragraph after Fig. 5",
          r"이 거리는 평균 60정도의 오차 거리를 보였다.",
          "This distance showed an error distance of about 60 on average."),
    Quote("kim2016.error_hog40", "§4, paragraph after Fig. 5",
          r"이는 평균 40정도의 오차 거리로, HSIcolor_오차거리에 비해 나은 결과를 보였다.",
          "This is an error distance of about 40 on average, a better result than the HSI "
          "colour error distance."),
    Quote("kim2016.error_proposed", "§4, paragraph after Fig. 5",
          r"proposed_오차거리는 평균 15에서 20정도의 오차 거리를 보였다.",
          "the proposed error distance showed an error distance of about 15 to 20 on average."),
    Quote("kim2016.bending_unstable", "§5, second paragraph",
          r"실험 결과에서와 달리, 객체가 구부러지는 것과 같이 변화가 있는 객체를 추적하면 초기화 "
          r"단계에서 생성된 에지 관측 모델과 달라지기 때문에 오차의 가능성이 있어서 불안정한 "
          r"성능을 보였다.",
          "Unlike in the experimental results, tracking an object that changes, for example "
          "one that bends, showed unstable performance, because it differs from the edge "
          "observation model built in the initialisation step, which makes errors possible."),
    Quote("kim2016.model_not_updated", "§5, second paragraph",
          r"향후 다양한 분야에 적용하기 위해 객체의 변화에 따라 에지 관측 모델을 업데이트하거나 "
          r"여러 특징을 혼합하여 모델링을 하는 방법에 대한 추가적인 연구가 필요하다.",
          "To apply it to various fields, further research is needed on updating the edge "
          "observation model as the object changes, or on modelling with several features "
          "combined."),
    Quote("kim2016.abstract_real_time", "Abstract (English)",
          r"In this paper, we propose a method that is tracking an object in real time using "
          r"particle filter and the observation model with edge.",
          "In this paper, we propose a method that is tracking an object in real time using "
          "particle filter and the observation model with edge."),
    Quote("kim2016.baselines_reason", "§4, first paragraph",
          r"표 1에서 보듯이, 파티클 필터에 사용되는 객체 특징 중 많이 사용되는 HSI 색상 모델과 HOG "
          r"특징을 이용하여 파티클 필터의 객체 추적 성능을 비교하기 위한 방법으로 사용하였다.",
          "As Table 1 shows, the HSI colour model and the HOG feature, widely used object "
          "features of particle filters, were used as the methods against which the particle "
          "filter's tracking performance is compared."),
]
