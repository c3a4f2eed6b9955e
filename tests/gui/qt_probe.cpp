// A test hook preloaded into the MeshLab GUI (LD_PRELOAD) by tests/gui/gui_test.py. Every 250 ms it
// writes what a user sees to $ACD_GUI_PROBE as JSON: the open menus with each entry's screen
// rectangle, the layer and log panels, and the filter dialog's labels, fields and buttons. The test
// drives MeshLab with real X events (xdotool) and uses this only to know where to click and what
// appeared; it never calls MeshLab itself.
#include <QApplication>
#include <QFile>
#include <QHeaderView>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QTimer>
#include <QTreeWidget>

namespace {

QJsonArray rect(const QWidget* w, const QRect& r)
{
	const QPoint p = w->mapToGlobal(r.topLeft());
	return QJsonArray{p.x(), p.y(), r.width(), r.height()};
}

void dump()
{
	QJsonArray menus, trees, labels, fields, buttons, windows, views;
	QString    log;
	for (QWidget* top : QApplication::topLevelWidgets()) {
		if (!top->isVisible()) continue;
		windows.append(QJsonObject{{"title", top->windowTitle()}, {"class", top->metaObject()->className()}});
		if (auto* m = qobject_cast<QMenu*>(top)) {
			QJsonArray entries;
			for (QAction* a : m->actions())
				if (a->isVisible() && !a->isSeparator())
					entries.append(QJsonObject{{"text", a->text().remove('&')},
					                           {"submenu", a->menu() != nullptr},
					                           {"rect", rect(m, m->actionGeometry(a))}});
			menus.append(QJsonObject{{"title", m->title().remove('&')}, {"entries", entries}});
		}
		for (auto* t : top->findChildren<QTreeWidget*>()) {
			if (!t->isVisible()) continue;
			QJsonArray items;
			for (int i = 0; i < t->topLevelItemCount(); ++i) {
				QTreeWidgetItem* it = t->topLevelItem(i);
				QJsonArray       cols;
				const QRect      row = t->visualItemRect(it);
				for (int c = 0; c < t->columnCount(); ++c) {
					const QRect cell(t->header()->sectionPosition(c), row.y(), t->header()->sectionSize(c), row.height());
					cols.append(QJsonObject{{"text", it->text(c)}, {"rect", rect(t->viewport(), cell)}});
				}
				items.append(cols);
			}
			trees.append(QJsonObject{{"name", t->objectName()}, {"items", items}});
		}
		for (auto* v : top->findChildren<QWidget*>())
			if (v->isVisible() && QString(v->metaObject()->className()) == "GLArea")
				views.append(rect(v, v->rect()));
		for (auto* l : top->findChildren<QPlainTextEdit*>())
			if (l->objectName() == "logPlainTextEdit") log = l->toPlainText().right(4000);
		for (auto* l : top->findChildren<QLabel*>())
			if (l->isVisible() && !l->text().isEmpty())
				labels.append(QJsonObject{{"text", l->text()}, {"tooltip", l->toolTip()}, {"rect", rect(l, l->rect())}});
		for (auto* e : top->findChildren<QLineEdit*>())
			if (e->isVisible())
				fields.append(QJsonObject{{"text", e->text()}, {"tooltip", e->toolTip()}, {"rect", rect(e, e->rect())}});
		for (auto* b : top->findChildren<QPushButton*>())
			if (b->isVisible())
				buttons.append(QJsonObject{{"text", b->text().remove('&')}, {"name", b->objectName()}, {"rect", rect(b, b->rect())}});
	}
	const QJsonObject all{{"menus", menus}, {"trees", trees},  {"log", log},        {"labels", labels},
	                      {"fields", fields}, {"buttons", buttons}, {"windows", windows},
	                      {"views", views}};
	const QString path = qEnvironmentVariable("ACD_GUI_PROBE");
	QFile         f(path + ".tmp");
	if (!f.open(QIODevice::WriteOnly)) return;
	f.write(QJsonDocument(all).toJson(QJsonDocument::Compact));
	f.close();
	QFile::remove(path);
	QFile::rename(path + ".tmp", path);   // readers never see half a file
}

void start()
{
	if (qEnvironmentVariableIsEmpty("ACD_GUI_PROBE") || !qobject_cast<QApplication*>(QCoreApplication::instance()))
		return;
	auto* timer = new QTimer(QCoreApplication::instance());
	QObject::connect(timer, &QTimer::timeout, dump);
	timer->start(250);
}

} // namespace

Q_COREAPP_STARTUP_FUNCTION(start)
