// Every string of the dashboard in English, French and Romanian.  Elements carry
// data-i18n="key" (text), data-i18n-title / data-i18n-placeholder / data-i18n-aria (attributes);
// code calls t(key, values).  The chosen language is kept in localStorage.

export const LANGS = { en: "English", fr: "Français", ro: "Română" };

const STRINGS = {
  en: {
    title: "amiro dashboard", signin_title: "amiro — sign in", user: "User", password: "Password",
    sign_in: "Sign in", wrong_login: "Wrong user or password.", sign_out: "Sign out",
    language: "Language", estop: "Emergency stop", estop_release: "Release stop",
    estop_engaged: "Emergency stop engaged: the robot does not move.", fall: "Fall!",
    fall_title: "Raise a fall alarm for the first resident (priority 100, preempts other behaviours)",
    home: "Home", zoom_in: "Zoom in", zoom_out: "Zoom out", fit: "Fit", lidar: "Lidar scan",
    robot_at: "Robot at", unknown: "unknown", legend_open: "open door", legend_closed: "closed door",
    legend_path: "planned path", legend_robot: "robot", legend_person: "person",
    behaviours: "Behaviours", running: "Running", nothing: "nothing", queue: "Queue",
    queue_empty: "The queue is empty.", priority: "priority", scenarios: "Scenarios", tasks: "Tasks",
    started_for: "for {s} s", scenario_started: "Scenario {name} started ({id}, priority {priority})",
    task_queued: "Task {type} queued ({run})", timeline: "Timeline",
    timeline_empty: "No events yet: start a scenario.", conversation: "Conversation",
    as_me: "as me", as_person: "as {name}", speaker: "who is speaking", say_something: "Say something to the robot",
    send: "Send", speak: "Speak replies", smart_home: "Smart home", lights: "Lights", blinds: "Blinds",
    on: "on", off: "off", open: "open", closed: "closed", heat: "Heat to 31 °C",
    heat_title: "Set the simulated temperature of this room to 31.5 °C (the hot-room rule fires)",
    temperature: "Temperature", humidity: "Humidity", luminosity: "Light",
    health: "Health", person: "Person", metric: "Measure", demo: "DEMO DATA",
    demo_title: "Seeded demo measurements, not a real person's (web.demo_data: false turns them off)",
    no_health: "No health data yet.", latest: "Latest", trend: "Trend", per_day: "per day",
    reference: "Reference range", no_latest: "no measurement",
    rising: "rising", falling: "falling", stable: "stable", unknown_trend: "not enough data",
    blood_pressure: "Blood pressure", heart_rate: "Heart rate", steps: "Steps", sleep: "Sleep",
    systolic: "systolic", diastolic: "diastolic", value: "value", day_axis: "day",
    notifications: "Notifications", no_notifications: "No acknowledgements yet.",
    // timeline narration
    ev_notification: "Alert: {reason} → {kind} for {user}",
    ev_graph_submitted: "Behaviour {graph} queued (priority {priority})",
    ev_graph_suspended: "Behaviour {graph} put aside for {by}", ev_graph_resumed: "Behaviour {graph} resumes",
    ev_task_started: "▶ {task_type} [{task}]", ev_task_success: "✔ {task_type} [{task}] succeeded",
    ev_task_failure: "✘ {task_type} [{task}] {result}", ev_task_preempted: "⏸ {task} preempted by {by}",
    ev_graph_finished: "Behaviour {graph} finished: {outcome}", ev_say: "Robot says ({lang}): “{text}”",
    ev_heard: "Heard {speaker}: “{text}” → {intent}", ev_person_found: "Found {person} in the {room}",
    ev_search_room: "Not seen here; looking in the {room}", ev_activity_recognised: "Saw {person}: {activity}",
    ev_ack: "Acknowledged {id} to the smart home: {status}", ev_fall_detected: "Fall detected: {person}",
    ev_plan: "Plan {number}: {summary}", ev_replan: "Re-planning: {reason}", ev_plan_failed: "No plan: {explanation}",
    ev_plan_completed: "Errand completed ({plans} plan(s))", ev_chat: "{who}: {text}",
    someone: "someone",
    w_done: "done", w_postponed: "postponed", w_failed: "failed", w_completed: "completed", w_cancelled: "cancelled", w_person_not_found: "person not found", w_person_unreachable: "person unreachable", w_not_confirmed: "not confirmed", w_confirmed_by_voice: "confirmed by voice", w_success: "succeeded", w_failure: "failed", w_preempted: "preempted", w_drink_water: "drinking water", w_standing_up: "standing up", w_hand_waving: "waving", w_play_phone: "on the phone", w_typing: "typing", w_pointing: "pointing", w_sneeze_cough: "sneezing or coughing", w_touch_chest: "touching the chest", w_falling: "falling", w_idle: "resting", w_living_room: "living room", w_kitchen: "kitchen", w_bedroom: "bedroom", w_bathroom: "bathroom", w_hallway: "hallway", w_steps: "steps", w_hydration: "hydration", w_fall: "fall", w_go_to: "go to",
    w_Say: "Say", w_Display: "Show on screen", w_MoveTo: "Go to", w_Wait: "Wait", w_Search: "Search for a person", w_Listen: "Listen", w_RecognizeActivity: "Watch the activity", w_NotifyEnvironment: "Report to the home", w_Check: "Check a condition", w_CheckDoor: "Check a door", w_Sequence: "Steps one after another",
  },
  fr: {
    title: "Tableau de bord amiro", signin_title: "amiro — connexion", user: "Utilisateur", password: "Mot de passe",
    sign_in: "Se connecter", wrong_login: "Utilisateur ou mot de passe incorrect.", sign_out: "Se déconnecter",
    language: "Langue", estop: "Arrêt d'urgence", estop_release: "Relâcher l'arrêt",
    estop_engaged: "Arrêt d'urgence enclenché : le robot ne bouge pas.", fall: "Chute !",
    fall_title: "Signaler une chute du premier résident (priorité 100, interrompt les autres comportements)",
    home: "Logement", zoom_in: "Zoomer", zoom_out: "Dézoomer", fit: "Ajuster", lidar: "Balayage lidar",
    robot_at: "Robot à", unknown: "inconnue", legend_open: "porte ouverte", legend_closed: "porte fermée",
    legend_path: "trajet prévu", legend_robot: "robot", legend_person: "personne",
    behaviours: "Comportements", running: "En cours", nothing: "rien", queue: "File d'attente",
    queue_empty: "La file d'attente est vide.", priority: "priorité", scenarios: "Scénarios", tasks: "Tâches",
    started_for: "depuis {s} s", scenario_started: "Scénario {name} lancé ({id}, priorité {priority})",
    task_queued: "Tâche {type} en file ({run})", timeline: "Chronologie",
    timeline_empty: "Aucun événement : lancez un scénario.", conversation: "Conversation",
    as_me: "en mon nom", as_person: "au nom de {name}", speaker: "qui parle", say_something: "Dites quelque chose au robot",
    send: "Envoyer", speak: "Lire les réponses", smart_home: "Maison connectée", lights: "Lumières", blinds: "Stores",
    on: "allumées", off: "éteintes", open: "ouverts", closed: "fermés", heat: "Chauffer à 31 °C",
    heat_title: "Régler la température simulée de la pièce à 31,5 °C (la règle « pièce chaude » se déclenche)",
    temperature: "Température", humidity: "Humidité", luminosity: "Lumière",
    health: "Santé", person: "Personne", metric: "Mesure", demo: "DONNÉES DE DÉMO",
    demo_title: "Mesures de démonstration générées, pas celles d'une vraie personne (web.demo_data: false les désactive)",
    no_health: "Pas encore de données de santé.", latest: "Dernière mesure", trend: "Tendance", per_day: "par jour",
    reference: "Plage de référence", no_latest: "aucune mesure",
    rising: "en hausse", falling: "en baisse", stable: "stable", unknown_trend: "pas assez de données",
    blood_pressure: "Tension artérielle", heart_rate: "Fréquence cardiaque", steps: "Pas", sleep: "Sommeil",
    systolic: "systolique", diastolic: "diastolique", value: "valeur", day_axis: "jour",
    notifications: "Notifications", no_notifications: "Aucun accusé de réception.",
    ev_notification: "Alerte : {reason} → {kind} pour {user}",
    ev_graph_submitted: "Comportement {graph} en file (priorité {priority})",
    ev_graph_suspended: "Comportement {graph} mis de côté pour {by}", ev_graph_resumed: "Le comportement {graph} reprend",
    ev_task_started: "▶ {task_type} [{task}]", ev_task_success: "✔ {task_type} [{task}] réussie",
    ev_task_failure: "✘ {task_type} [{task}] {result}", ev_task_preempted: "⏸ {task} interrompue par {by}",
    ev_graph_finished: "Comportement {graph} terminé : {outcome}", ev_say: "Le robot dit ({lang}) : « {text} »",
    ev_heard: "Entendu {speaker} : « {text} » → {intent}", ev_person_found: "{person} trouvée : {room}",
    ev_search_room: "Pas vue ici ; recherche : {room}", ev_activity_recognised: "Vu {person} : {activity}",
    ev_ack: "Accusé {id} envoyé à la maison : {status}", ev_fall_detected: "Chute détectée : {person}",
    ev_plan: "Plan {number} : {summary}", ev_replan: "Nouveau plan : {reason}", ev_plan_failed: "Aucun plan : {explanation}",
    ev_plan_completed: "Course terminée ({plans} plan(s))", ev_chat: "{who} : {text}",
    someone: "quelqu'un",
    w_done: "fait", w_postponed: "reporté", w_failed: "échec", w_completed: "terminé", w_cancelled: "annulé", w_person_not_found: "personne introuvable", w_person_unreachable: "personne inaccessible", w_not_confirmed: "non confirmé", w_confirmed_by_voice: "confirmé à la voix", w_success: "réussie", w_failure: "échouée", w_preempted: "interrompue", w_drink_water: "boit de l'eau", w_standing_up: "se lève", w_hand_waving: "fait signe", w_play_phone: "au téléphone", w_typing: "tape au clavier", w_pointing: "montre du doigt", w_sneeze_cough: "éternue ou tousse", w_touch_chest: "se touche la poitrine", w_falling: "tombe", w_idle: "se repose", w_living_room: "salon", w_kitchen: "cuisine", w_bedroom: "chambre", w_bathroom: "salle de bain", w_hallway: "couloir", w_steps: "pas", w_hydration: "hydratation", w_fall: "chute", w_go_to: "aller à",
    w_Say: "Dire", w_Display: "Afficher à l’écran", w_MoveTo: "Aller à", w_Wait: "Attendre", w_Search: "Chercher une personne", w_Listen: "Écouter", w_RecognizeActivity: "Observer l’activité", w_NotifyEnvironment: "Informer la maison", w_Check: "Vérifier une condition", w_CheckDoor: "Vérifier une porte", w_Sequence: "Étapes l’une après l’autre",
  },
  ro: {
    title: "Panoul amiro", signin_title: "amiro — autentificare", user: "Utilizator", password: "Parolă",
    sign_in: "Autentificare", wrong_login: "Utilizator sau parolă greșită.", sign_out: "Deconectare",
    language: "Limba", estop: "Oprire de urgență", estop_release: "Anulează oprirea",
    estop_engaged: "Oprire de urgență activă: robotul nu se mișcă.", fall: "Cădere!",
    fall_title: "Semnalează o cădere a primului locatar (prioritate 100, întrerupe celelalte comportamente)",
    home: "Locuința", zoom_in: "Mărește", zoom_out: "Micșorează", fit: "Încadrează", lidar: "Scanare lidar",
    robot_at: "Robotul la", unknown: "necunoscut", legend_open: "ușă deschisă", legend_closed: "ușă închisă",
    legend_path: "traseu planificat", legend_robot: "robot", legend_person: "persoană",
    behaviours: "Comportamente", running: "Rulează", nothing: "nimic", queue: "Coadă",
    queue_empty: "Coada este goală.", priority: "prioritate", scenarios: "Scenarii", tasks: "Sarcini",
    started_for: "de {s} s", scenario_started: "Scenariul {name} a pornit ({id}, prioritate {priority})",
    task_queued: "Sarcina {type} în coadă ({run})", timeline: "Cronologie",
    timeline_empty: "Niciun eveniment: porniți un scenariu.", conversation: "Conversație",
    as_me: "în numele meu", as_person: "în numele lui {name}", speaker: "cine vorbește", say_something: "Spuneți ceva robotului",
    send: "Trimite", speak: "Citește răspunsurile", smart_home: "Casa inteligentă", lights: "Lumini", blinds: "Jaluzele",
    on: "aprinse", off: "stinse", open: "deschise", closed: "închise", heat: "Încălzește la 31 °C",
    heat_title: "Setează temperatura simulată a camerei la 31,5 °C (regula „cameră caldă” se declanșează)",
    temperature: "Temperatură", humidity: "Umiditate", luminosity: "Lumină",
    health: "Sănătate", person: "Persoană", metric: "Măsurătoare", demo: "DATE DEMO",
    demo_title: "Măsurători demonstrative generate, nu ale unei persoane reale (web.demo_data: false le oprește)",
    no_health: "Încă nu există date de sănătate.", latest: "Ultima măsurătoare", trend: "Tendință", per_day: "pe zi",
    reference: "Interval de referință", no_latest: "nicio măsurătoare",
    rising: "în creștere", falling: "în scădere", stable: "stabilă", unknown_trend: "date insuficiente",
    blood_pressure: "Tensiune arterială", heart_rate: "Puls", steps: "Pași", sleep: "Somn",
    systolic: "sistolică", diastolic: "diastolică", value: "valoare", day_axis: "zi",
    notifications: "Notificări", no_notifications: "Nicio confirmare încă.",
    ev_notification: "Alertă: {reason} → {kind} pentru {user}",
    ev_graph_submitted: "Comportamentul {graph} în coadă (prioritate {priority})",
    ev_graph_suspended: "Comportamentul {graph} pus deoparte pentru {by}", ev_graph_resumed: "Comportamentul {graph} continuă",
    ev_task_started: "▶ {task_type} [{task}]", ev_task_success: "✔ {task_type} [{task}] reușită",
    ev_task_failure: "✘ {task_type} [{task}] {result}", ev_task_preempted: "⏸ {task} întreruptă de {by}",
    ev_graph_finished: "Comportamentul {graph} s-a încheiat: {outcome}", ev_say: "Robotul spune ({lang}): „{text}”",
    ev_heard: "Auzit {speaker}: „{text}” → {intent}", ev_person_found: "{person} găsită în {room}",
    ev_search_room: "Nu este aici; caută în {room}", ev_activity_recognised: "A văzut {person}: {activity}",
    ev_ack: "Confirmare {id} trimisă casei: {status}", ev_fall_detected: "Cădere detectată: {person}",
    ev_plan: "Planul {number}: {summary}", ev_replan: "Replanificare: {reason}", ev_plan_failed: "Niciun plan: {explanation}",
    ev_plan_completed: "Sarcină încheiată ({plans} plan(uri))", ev_chat: "{who}: {text}",
    someone: "cineva",
    w_done: "făcut", w_postponed: "amânat", w_failed: "eșuat", w_completed: "încheiat", w_cancelled: "anulat", w_person_not_found: "persoana nu a fost găsită", w_person_unreachable: "persoana nu poate fi atinsă", w_not_confirmed: "neconfirmat", w_confirmed_by_voice: "confirmat vocal", w_success: "reușită", w_failure: "eșuată", w_preempted: "întreruptă", w_drink_water: "bea apă", w_standing_up: "se ridică", w_hand_waving: "face cu mâna", w_play_phone: "la telefon", w_typing: "tastează", w_pointing: "arată cu degetul", w_sneeze_cough: "strănută sau tușește", w_touch_chest: "își atinge pieptul", w_falling: "cade", w_idle: "se odihnește", w_living_room: "sufragerie", w_kitchen: "bucătărie", w_bedroom: "dormitor", w_bathroom: "baie", w_hallway: "hol", w_steps: "pași", w_hydration: "hidratare", w_fall: "cădere", w_go_to: "deplasare",
    w_Say: "Spune", w_Display: "Afișează pe ecran", w_MoveTo: "Mergi la", w_Wait: "Așteaptă", w_Search: "Caută o persoană", w_Listen: "Ascultă", w_RecognizeActivity: "Urmărește activitatea", w_NotifyEnvironment: "Anunță casa", w_Check: "Verifică o condiție", w_CheckDoor: "Verifică o ușă", w_Sequence: "Pași unul după altul",
  },
};

export const SPEECH_LANG = { en: "en-GB", fr: "fr-FR", ro: "ro-RO" };

export function strings(lang) { return STRINGS[lang]; }

function initialLang() {
  const kept = localStorage.getItem("amiro.lang");
  if (kept in STRINGS) return kept;
  const browser = (navigator.language || "en").slice(0, 2);
  return browser in STRINGS ? browser : "en";
}

let current = initialLang();

export function lang() { return current; }

export function t(key, values = {}) {
  const text = STRINGS[current][key] ?? STRINGS.en[key] ?? key;
  return text.replace(/\{(\w+)\}/g, (_, k) => (values[k] ?? ""));
}

export function translatePage(root = document) {
  document.documentElement.lang = current;
  for (const el of root.querySelectorAll("[data-i18n]")) el.textContent = t(el.dataset.i18n);
  for (const el of root.querySelectorAll("[data-i18n-title]")) el.title = t(el.dataset.i18nTitle);
  for (const el of root.querySelectorAll("[data-i18n-placeholder]")) el.placeholder = t(el.dataset.i18nPlaceholder);
  for (const el of root.querySelectorAll("[data-i18n-aria]")) el.setAttribute("aria-label", t(el.dataset.i18nAria));
  const title = document.querySelector("title[data-i18n]");
  if (title) document.title = title.textContent;
}

// A data word (room, activity, outcome, status): its translation when there is one, else
// the word itself, made readable.
export function word(name) {
  const key = `w_${name}`;
  return STRINGS[current][key] ?? STRINGS.en[key] ?? String(name ?? "").replace(/_/g, " ");
}

export function setLang(next, onChange) {
  if (!(next in STRINGS)) return;
  current = next;
  localStorage.setItem("amiro.lang", next);
  translatePage();
  if (onChange) onChange(next);
}

export function languageSelect(select, onChange) {
  select.replaceChildren(...Object.entries(LANGS).map(([code, name]) => new Option(name, code)));
  select.value = current;
  select.addEventListener("change", () => setLang(select.value, onChange));
}
