package io.dtron.xta.internal;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.Fragment;
import io.dtron.xta.LineMap;
import io.dtron.xta.Pos;
import io.dtron.xta.ast.Coord;
import io.dtron.xta.ast.Decl;
import io.dtron.xta.ast.Edge;
import io.dtron.xta.ast.Expr;
import io.dtron.xta.ast.Label;
import io.dtron.xta.ast.Location;
import io.dtron.xta.ast.Nta;
import io.dtron.xta.ast.Param;
import io.dtron.xta.ast.Query;
import io.dtron.xta.ast.SystemLine;
import io.dtron.xta.internal.parser.UppaalParser;
import java.io.StringReader;
import java.util.ArrayList;
import java.util.List;
import java.util.function.Function;
import javax.xml.stream.XMLInputFactory;
import javax.xml.stream.XMLStreamConstants;
import javax.xml.stream.XMLStreamException;
import javax.xml.stream.XMLStreamReader;
import org.antlr.v4.runtime.ParserRuleContext;

/**
 * Reads the Uppaal XML container (DTD flat-1_0 to flat-1_6 and later): global declarations, templates with
 * their locations, branchpoints, transitions and labels, the instantiation and system sections and the
 * queries. Each label's text is parsed by the grammar rule for its kind, with positions that point into the
 * XML file. The DTD is never fetched and no external entity is resolved.
 */
final class XmlModelReader {
    private final String file;
    private final String raw;
    private final LineMap lines;
    private final List<Diagnostic> diagnostics;
    private XMLStreamReader reader;
    private String currentTemplate;

    private XmlModelReader(String file, String raw, List<Diagnostic> diagnostics) {
        this.file = file;
        this.raw = raw;
        this.lines = LineMap.of(raw);
        this.diagnostics = diagnostics;
    }

    /** The model in {@code text}, or null when the XML itself is unreadable (errors added to {@code out}). */
    static Nta read(String file, String text, List<Diagnostic> out) {
        return new XmlModelReader(file, text, out).read();
    }

    private Nta read() {
        XMLInputFactory factory = XMLInputFactory.newFactory();
        factory.setProperty(XMLInputFactory.SUPPORT_DTD, false);
        factory.setProperty(XMLInputFactory.IS_SUPPORTING_EXTERNAL_ENTITIES, false);
        // not coalescing: the reader would hold the whole of a large text in a buffer of its own (2 bytes per
        // character) until the end of the file; elementText() joins the pieces instead
        factory.setProperty(XMLInputFactory.IS_COALESCING, false);
        List<Decl> globals = new ArrayList<>();
        List<Decl> templates = new ArrayList<>();
        List<Decl> systemDecls = new ArrayList<>();
        List<Query> queries = new ArrayList<>();
        SystemLine system = null;
        try {
            reader = factory.createXMLStreamReader(new StringReader(raw));
            while (reader.hasNext() && reader.next() != XMLStreamConstants.START_ELEMENT) {
                // skip the prolog
            }
            if (!reader.isStartElement()) {
                diagnostics.add(Diagnostic.error(new Pos(whole(), 0, 0), "not an Uppaal model: the XML has no elements"));
                return null;
            }
            if (!reader.getLocalName().equals("nta")) {
                int at = posOfTag().fragment().fileOffset(0);
                diagnostics.add(Diagnostic.error(new Pos(whole(), at, at),
                        "not an Uppaal model: the root element is <"
                        + reader.getLocalName() + ">, expected <nta>"));
                return null;
            }
            while (nextChild()) {
                switch (reader.getLocalName()) {
                    case "declaration" -> globals.addAll(parseDeclarations(text("declaration")));
                    case "template" -> templates.add(template());
                    case "instantiation", "system" -> {
                        String kind = reader.getLocalName();
                        AstBuilder.Section parts = parseSystem(text(kind));
                        systemDecls.addAll(parts.declarations());
                        if (parts.system() != null) {
                            system = parts.system();
                        }
                    }
                    case "queries" -> queries(queries);
                    default -> {
                        diagnostics.add(Diagnostic.warning(posOfTag(), "element <" + reader.getLocalName()
                                + "> is not part of an Uppaal model and is ignored"));
                        skipElement();
                    }
                }
            }
        } catch (XMLStreamException e) {
            int offset = e.getLocation() == null ? 0
                    : lines.offset(e.getLocation().getLineNumber(), Math.max(1, e.getLocation().getColumnNumber()));
            offset = Math.max(0, Math.min(offset, raw.length()));
            diagnostics.add(Diagnostic.error(new Pos(whole(), offset, offset), xmlError(xmlMessage(e))));
            return null;
        }
        List<Decl> all = new ArrayList<>(globals);
        all.addAll(templates);
        all.addAll(systemDecls);
        return new Nta(file, all, system, queries);
    }

    private static final java.util.regex.Pattern UNDECLARED_ENTITY =
            java.util.regex.Pattern.compile("The entity \"([^\"]+)\" was referenced, but not declared\\.?");

    /**
     * The message for an XML error: an entity that the DOCTYPE declares is not "not declared", it is unread,
     * because DTRON reads no DTD (by design: nothing is fetched, no entity of a DOCTYPE is expanded).
     */
    private String xmlError(String message) {
        java.util.regex.Matcher m = UNDECLARED_ENTITY.matcher(message);
        if (m.matches()) {
            String name = m.group(1);
            int doctype = raw.indexOf("<!DOCTYPE");
            int root = raw.indexOf("<nta");
            if (doctype >= 0 && java.util.regex.Pattern.compile("<!ENTITY\\s+" + java.util.regex.Pattern.quote(name)
                    + "\\s").matcher(raw.substring(doctype, root < doctype ? raw.length() : root)).find()) {
                return "the entity '&" + name + ";' is declared in the DOCTYPE, but DTRON reads no DTD, by design"
                        + " (nothing is fetched and no entity of a DOCTYPE is expanded): write its text in place of &"
                        + name + ";";
            }
            return "malformed XML: the entity '&" + name + ";' is not declared (XML declares only &lt; &gt; &amp;"
                    + " &quot; &apos;)";
        }
        return "malformed XML: " + message;
    }

    /** The whole file as a fragment, for errors that concern the XML itself (made only then: it maps every line). */
    private Fragment whole() {
        return Fragment.ofFile(file, raw);
    }

    private static String xmlMessage(XMLStreamException e) {
        String m = e.getMessage() == null ? "unreadable" : e.getMessage();
        int i = m.indexOf("Message: ");
        return i >= 0 ? m.substring(i + "Message: ".length()).trim() : m.trim();
    }

    // ------------------------------------------------------------ templates

    private Decl.Template template() throws XMLStreamException {
        currentTemplate = null;
        String name = null;
        Pos namePos = posOfTag();
        Coord coord = null;
        List<Param> params = List.of();
        List<Decl> decls = new ArrayList<>();
        List<Location> locations = new ArrayList<>();
        List<String> branchpoints = new ArrayList<>();
        List<Edge> edges = new ArrayList<>();
        String init = null;
        Pos initPos = null;
        while (nextChild()) {
            switch (reader.getLocalName()) {
                case "name" -> {
                    coord = coord();
                    Fragment f = text("name");
                    name = f.text().trim();
                    currentTemplate = name;
                    namePos = trimmedPos(f.withTemplate(name));
                }
                case "parameter" -> params = parseParams(text("parameter"));
                case "declaration" -> decls.addAll(parseDeclarations(text("declaration")));
                case "location" -> locations.add(location());
                case "branchpoint" -> {
                    branchpoints.add(attribute("id"));
                    skipElement();
                }
                case "init" -> {
                    init = attribute("ref");
                    initPos = posOfTag();
                    skipElement();
                }
                case "transition" -> edges.add(transition());
                default -> skipElement();
            }
        }
        currentTemplate = null;
        if (name == null || name.isEmpty()) {
            diagnostics.add(Diagnostic.error(namePos, "template without a name"));
            name = "?";
        }
        return new Decl.Template(namePos, name, params, decls, locations, branchpoints, init, initPos, edges, coord);
    }

    private Location location() throws XMLStreamException {
        String id = attribute("id");
        Coord coord = coord();
        Pos pos = posOfTag();
        String name = null;
        Location.Kind kind = Location.Kind.NORMAL;
        Expr invariant = null;
        List<Label> labels = new ArrayList<>();
        while (nextChild()) {
            switch (reader.getLocalName()) {
                case "name" -> {
                    Coord c = coord();
                    Fragment f = text("location name");
                    labels.add(new Label("name", f.text(), c));
                    name = f.text().trim();
                    pos = trimmedPos(f);
                }
                case "label" -> {
                    String labelKind = attribute("kind");
                    Coord c = coord();
                    Fragment f = text(labelKind == null ? "label" : labelKind);
                    labels.add(new Label(f.kind(), f.text(), c));
                    if ("invariant".equals(labelKind) && !f.text().isBlank()) {
                        UppaalParser.InvariantLabelContext ctx = parseRule(f, UppaalParser::invariantLabel);
                        if (ctx != null) {
                            invariant = new AstBuilder(f, diagnostics).expr(ctx.guardExpr().expression());
                        }
                    }
                }
                case "urgent" -> {
                    kind = Location.Kind.URGENT;
                    skipElement();
                }
                case "committed" -> {
                    kind = Location.Kind.COMMITTED;
                    skipElement();
                }
                default -> skipElement();
            }
        }
        return new Location(pos, id, name == null || name.isEmpty() ? null : name, kind, invariant, coord, labels);
    }

    private Edge transition() throws XMLStreamException {
        Pos pos = posOfTag();
        String source = null;
        String target = null;
        List<Coord> nails = new ArrayList<>();
        List<Label> labels = new ArrayList<>();
        List<Edge.Select> selects = List.of();
        Expr guard = null;
        Edge.Sync sync = null;
        List<Expr> updates = List.of();
        Expr probability = null;
        while (nextChild()) {
            switch (reader.getLocalName()) {
                case "source" -> {
                    source = attribute("ref");
                    skipElement();
                }
                case "target" -> {
                    target = attribute("ref");
                    skipElement();
                }
                case "nail" -> {
                    nails.add(coord());
                    skipElement();
                }
                case "label" -> {
                    String kind = attribute("kind");
                    Coord c = coord();
                    Fragment f = text(kind == null ? "label" : kind);
                    labels.add(new Label(f.kind(), f.text(), c));
                    if (f.text().isBlank()) {
                        continue;
                    }
                    AstBuilder builder = new AstBuilder(f, diagnostics);
                    switch (f.kind()) {
                        case "select" -> {
                            UppaalParser.SelectLabelContext ctx = parseRule(f, UppaalParser::selectLabel);
                            if (ctx != null) {
                                selects = ctx.selectItem().stream().map(builder::select).toList();
                            }
                        }
                        case "guard" -> {
                            UppaalParser.GuardLabelContext ctx = parseRule(f, UppaalParser::guardLabel);
                            if (ctx != null) {
                                guard = builder.expr(ctx.guardExpr().expression());
                            }
                        }
                        case "synchronisation" -> {
                            UppaalParser.SyncLabelContext ctx = parseRule(f, UppaalParser::syncLabel);
                            if (ctx != null) {
                                sync = builder.sync(ctx.expression(), ctx.direction, builder.pos(ctx));
                            }
                        }
                        case "assignment" -> {
                            UppaalParser.UpdateLabelContext ctx = parseRule(f, UppaalParser::updateLabel);
                            if (ctx != null && ctx.expressionList() != null) {
                                updates = builder.exprs(ctx.expressionList().expression());
                            }
                        }
                        case "probability" -> {
                            UppaalParser.GuardLabelContext ctx = parseRule(f, UppaalParser::guardLabel);
                            if (ctx != null) {
                                probability = builder.expr(ctx.guardExpr().expression());
                            }
                        }
                        default -> {
                            // comments, testcode and the like carry no semantics for DTRON
                        }
                    }
                }
                default -> skipElement();
            }
        }
        return new Edge(pos, source, target, selects, guard, sync, updates, probability, nails, labels);
    }

    // ------------------------------------------------------------ label parsing

    private <T extends ParserRuleContext> T parseRule(Fragment f, Function<UppaalParser, T> rule) {
        return ParserDriver.parse(f, rule, diagnostics);
    }

    private List<Decl> parseDeclarations(Fragment f) {
        List<Decl> decls = Parsing.declarations(f, diagnostics);
        return decls == null ? List.of() : decls;
    }

    private AstBuilder.Section parseSystem(Fragment f) {
        AstBuilder.Section s = Parsing.section(f, UppaalParser::systemText, UppaalParser.SystemTextContext::topItem,
                UppaalParser.SystemTextContext::systemLine, diagnostics);
        return s == null ? new AstBuilder.Section(List.of(), null) : s;
    }

    private List<Param> parseParams(Fragment f) {
        UppaalParser.ParametersTextContext ctx = parseRule(f, UppaalParser::parametersText);
        return ctx == null ? List.of() : new AstBuilder(f, diagnostics).params(ctx.parameterList());
    }

    private void queries(List<Query> out) throws XMLStreamException {
        while (nextChild()) {
            if (!reader.getLocalName().equals("query")) {
                skipElement();
                continue;
            }
            Fragment formula = null;
            String comment = null;
            while (nextChild()) {
                switch (reader.getLocalName()) {
                    case "formula" -> formula = text("formula");
                    case "comment" -> comment = reader.getElementText().trim();
                    default -> skipElement();
                }
            }
            if (formula != null && !formula.text().isBlank()) {
                out.add(query(formula, comment));
            }
        }
    }

    /**
     * One query. Its syntax errors are the query's own: they are kept in the query (of kind
     * {@link Query.Kind#INVALID}) and never become errors of the model.
     */
    private static Query query(Fragment formula, String comment) {
        List<Diagnostic> errors = new ArrayList<>();
        UppaalParser.QueryTextContext ctx = ParserDriver.parse(formula, UppaalParser::queryText, errors);
        if (ctx != null && ctx.query() != null) {
            Query q = new AstBuilder(formula, errors).query(ctx.query(), comment);
            if (errors.isEmpty()) {
                return q;
            }
        }
        String t = formula.text();
        int start = 0;
        while (start < t.length() && Character.isWhitespace(t.charAt(start))) {
            start++;
        }
        int end = t.length();
        while (end > start && Character.isWhitespace(t.charAt(end - 1))) {
            end--;
        }
        Pos pos = new Pos(formula, start, end);
        return new Query(pos, Query.Kind.INVALID, pos.text(), null, null, null, comment, errors);
    }

    // ------------------------------------------------------------ StAX helpers

    /** Advances to the next child element of the current element; false at the current element's end. */
    private boolean nextChild() throws XMLStreamException {
        while (reader.hasNext()) {
            int event = reader.next();
            if (event == XMLStreamConstants.START_ELEMENT) {
                return true;
            }
            if (event == XMLStreamConstants.END_ELEMENT) {
                return false;
            }
        }
        return false;
    }

    private void skipElement() throws XMLStreamException {
        int depth = 1;
        while (depth > 0 && reader.hasNext()) {
            int event = reader.next();
            if (event == XMLStreamConstants.START_ELEMENT) {
                depth++;
            } else if (event == XMLStreamConstants.END_ELEMENT) {
                depth--;
            }
        }
    }

    private String attribute(String name) {
        return reader.getAttributeValue(null, name);
    }

    private Coord coord() {
        String x = attribute("x");
        String y = attribute("y");
        if (x == null || y == null) {
            return null;
        }
        try {
            return new Coord(Integer.parseInt(x.trim()), Integer.parseInt(y.trim()));
        } catch (NumberFormatException e) {
            return null;
        }
    }

    /** The offset just after the current start tag (where its content begins). */
    private int contentOffset() {
        javax.xml.stream.Location loc = reader.getLocation();
        int offset = lines.offset(loc.getLineNumber(), loc.getColumnNumber());
        offset = Math.max(0, Math.min(offset, raw.length()));
        if (offset > 0 && raw.charAt(offset - 1) == '>') {
            return offset;
        }
        int gt = raw.lastIndexOf('>', offset);
        return gt < 0 ? offset : gt + 1;
    }

    /** The current start tag, as a fragment of the current template named after the element. */
    private Pos posOfTag() {
        int end = contentOffset();
        int lt = raw.lastIndexOf('<', Math.max(0, end - 1));
        int start = lt < 0 ? end : lt;
        Fragment.Offsets offsets = new Fragment.Offsets();
        for (int i = start; i <= end; i++) {
            offsets.add(i);
        }
        Fragment tag = Fragment.ofPart(file, currentTemplate, reader.getLocalName(), raw.substring(start, end), lines,
                offsets);
        return new Pos(tag, 0, end - start);
    }

    /** The text of the current element as a fragment whose positions point into the file. */
    private Fragment text(String kind) throws XMLStreamException {
        int start = contentOffset();
        String content = elementText();
        Fragment.Offsets offsets = offsetsOf(content, start);
        if (offsets == null) {
            offsets = new Fragment.Offsets();
            for (int k = 0; k <= content.length(); k++) {
                offsets.add(Math.min(raw.length(), start + k));
            }
        }
        return Fragment.ofPart(file, currentTemplate, kind, content, lines, offsets);
    }

    /** The text content of the current element, read piece by piece up to its end tag, as getElementText. */
    private String elementText() throws XMLStreamException {
        String element = reader.getLocalName();
        StringBuilder text = new StringBuilder();
        while (true) {
            switch (reader.next()) {
                case XMLStreamConstants.CHARACTERS, XMLStreamConstants.CDATA, XMLStreamConstants.SPACE ->
                        text.append(reader.getTextCharacters(), reader.getTextStart(), reader.getTextLength());
                case XMLStreamConstants.ENTITY_REFERENCE -> text.append(reader.getText());
                case XMLStreamConstants.COMMENT, XMLStreamConstants.PROCESSING_INSTRUCTION -> {
                    // not part of the text
                }
                case XMLStreamConstants.END_ELEMENT -> {
                    return text.toString();
                }
                default -> throw new XMLStreamException("element <" + element + "> may contain only text",
                        reader.getLocation());
            }
        }
    }

    /**
     * Where each character of an element's decoded {@code content} stands in the file, reading the raw text
     * from {@code start} (entity references, CDATA sections, comments, line ends); null when the raw text does
     * not decode to the content.
     */
    private Fragment.Offsets offsetsOf(String content, int start) {
        Fragment.Offsets offsets = new Fragment.Offsets();
        int n = 0;
        int i = start;
        while (i < raw.length()) {
            if (raw.startsWith("<![CDATA[", i)) {
                int end = raw.indexOf("]]>", i);
                if (end < 0) {
                    return null;
                }
                for (int j = i + 9; j < end; j++) {
                    if (n >= content.length() || content.charAt(n) != raw.charAt(j)) {
                        return null;
                    }
                    offsets.add(j);
                    n++;
                }
                i = end + 3;
            } else if (raw.startsWith("<!--", i)) {
                int end = raw.indexOf("-->", i);
                i = end < 0 ? raw.length() : end + 3;
            } else if (raw.charAt(i) == '<') {
                break;
            } else if (raw.charAt(i) == '&') {
                int semi = raw.indexOf(';', i);
                String value = entity(semi < 0 ? "" : raw.substring(i + 1, semi));
                if (value == null || !content.startsWith(value, n)) {
                    return null;
                }
                for (int k = 0; k < value.length(); k++) {
                    offsets.add(i);
                }
                n += value.length();
                i = semi + 1;
            } else if (raw.charAt(i) == '\r') {
                // XML turns \r\n and lone \r into \n
                if (n >= content.length() || content.charAt(n) != '\n') {
                    return null;
                }
                offsets.add(i);
                n++;
                i += i + 1 < raw.length() && raw.charAt(i + 1) == '\n' ? 2 : 1;
            } else {
                if (n >= content.length() || content.charAt(n) != raw.charAt(i)) {
                    return null;
                }
                offsets.add(i);
                n++;
                i++;
            }
        }
        if (n != content.length()) {
            return null;
        }
        offsets.add(i);
        return offsets;
    }

    private static String entity(String name) {
        switch (name) {
            case "lt":
                return "<";
            case "gt":
                return ">";
            case "amp":
                return "&";
            case "quot":
                return "\"";
            case "apos":
                return "'";
            default:
                try {
                    if (name.startsWith("#x")) {
                        return new String(Character.toChars(Integer.parseInt(name.substring(2), 16)));
                    }
                    if (name.startsWith("#")) {
                        return new String(Character.toChars(Integer.parseInt(name.substring(1))));
                    }
                } catch (IllegalArgumentException e) {
                    return null;
                }
                return null;
        }
    }

    private Pos trimmedPos(Fragment f) {
        String t = f.text();
        int s = 0;
        while (s < t.length() && Character.isWhitespace(t.charAt(s))) {
            s++;
        }
        int e = t.length();
        while (e > s && Character.isWhitespace(t.charAt(e - 1))) {
            e--;
        }
        return new Pos(f, s, e);
    }
}
