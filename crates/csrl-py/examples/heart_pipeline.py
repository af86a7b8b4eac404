"""CS-ID3 on the Cleveland heart-disease records with each test's price, in a
scikit-learn pipeline (docs/python.md). Run from the repository's root."""

import csv

import numpy as np
from sklearn.compose import ColumnTransformer
from sklearn.model_selection import cross_validate
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import KBinsDiscretizer, OrdinalEncoder

from csrl.sklearn import CsId3Classifier

with open("data/heart-disease/cleveland.csv", encoding="utf-8") as f:
    rows = list(csv.DictReader(f))
with open("data/heart-disease/costs.csv", encoding="utf-8") as f:
    price = {r["feature"]: float(r["cost"]) for r in csv.DictReader(f)}
numeric = ["age", "trestbps", "chol", "thalch", "oldpeak"]
other = [c for c in rows[0] if c not in numeric and c != "num"]
X = np.array([[float(r[c]) for c in numeric] + [r[c] if r[c] != "?" else np.nan for c in other]
              for r in rows], dtype=object)
y = np.array([int(r["num"]) > 0 for r in rows])

prepare = ColumnTransformer([
    ("bins", KBinsDiscretizer(n_bins=4, encode="ordinal", strategy="uniform"), list(range(5))),
    ("codes", OrdinalEncoder(handle_unknown="use_encoded_value", unknown_value=-1), list(range(5, 13))),
])
model = make_pipeline(prepare, CsId3Classifier(feature_costs=[price[c] for c in numeric + other]))

scores = cross_validate(model, X, y, cv=10, return_estimator=True, return_indices=True)
costs = [est[-1].predict_cost(est[0].transform(X[test])).mean()
         for est, test in zip(scores["estimator"], scores["indices"]["test"])]
print(f"10-fold accuracy {scores['test_score'].mean():.3f}, "
      f"{np.mean(costs):.2f} per patient (every test: {sum(price.values()):.2f})")
