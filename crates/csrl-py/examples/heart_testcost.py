"""The test-cost tree family on the Cleveland heart-disease records, numeric columns as
they are, with Turney's prices, groups and discounts (docs/python.md). Run from the
repository's root."""

import csv

import numpy as np
import pandas as pd
from sklearn.model_selection import StratifiedKFold, cross_validate

from csrl.sklearn import C45Classifier, DtmcClassifier, Eg2Classifier, IcetClassifier, IdxClassifier

data = pd.read_csv("data/heart-disease/cleveland.csv")
X, y = data.drop(columns="num"), np.where(data["num"] > 0, "sick", "well")
with open("data/heart-disease/costs.csv", encoding="utf-8") as f:
    price = {r["feature"]: float(r["cost"]) for r in csv.DictReader(f)}
# Turney's groups: a second test of a group costs its discount price.
group = {"chol": "A", "fbs": "A", "thalch": "B", "thal": "B", "exang": "C", "oldpeak": "C", "slope": "C"}
discount = {"chol": 5.17, "fbs": 3.10, "thalch": 1.0, "thal": 1.0, "exang": 1.0, "oldpeak": 1.0, "slope": 1.0}
costs = dict(feature_costs=price, feature_groups=group, feature_discounts=discount, misclassification_cost=500.0)


def tests(est, X, y):
    return est.predict_cost(X).mean()


def total(est, X, y):
    return est.total_cost(X, y)


print(f"{'learner':8} {'accuracy':>8} {'tests':>7} {'total':>7}")
for name, model in [
    ("C4.5", C45Classifier(**costs)),
    ("IDX", IdxClassifier(**costs)),
    ("EG2", Eg2Classifier(**costs)),
    ("DTMC", DtmcClassifier(**costs)),
    ("ICET", IcetClassifier(seed=1, **costs)),
]:
    s = cross_validate(model, X, y, cv=StratifiedKFold(10, shuffle=True, random_state=1),
                       scoring={"accuracy": "accuracy", "tests": tests, "total": total})
    print(f"{name:8} {s['test_accuracy'].mean():8.3f} {s['test_tests'].mean():7.2f} {s['test_total'].mean():7.2f}")
print(f"every test: {sum(price.values()):.2f}")
