/*
 * The textual languages of Uppaal 4.x/5.x: declarations, templates in XTA
 * syntax, the system definition, the old Uppaal 3 syntax, label languages
 * (select, guard, synchronisation, update, invariant, probability) and the whole query language
 * (symbolic, statistical, strategies, scenarios).
 *
 * One grammar with one entry rule per kind of text, so that every label of an
 * XML model is parsed by the rule for its kind.
 */
grammar Uppaal;

// ---------------------------------------------------------------- entry rules

/** A whole .xta or .ta file. */
xtaFile : topItem* systemLine? trailer* EOF ;

/** A <declaration> element (global or template-local). */
declarationsText : declaration* EOF ;

/** A <system> (or <instantiation>) element: declarations, instantiations, the system line. */
systemText : topItem* systemLine? trailer* EOF ;

/** What follows the top-level items of an .xta file or a system section, when those are parsed one by one. */
sectionEnd : systemLine? trailer* EOF ;

/** A <parameter> element. */
parametersText : parameterList? EOF ;

selectLabel : selectItem (',' selectItem)* EOF ;
guardLabel : guardExpr EOF ;
invariantLabel : guardExpr EOF ;
syncLabel : expression direction=('!' | '?')? EOF ;
updateLabel : expressionList? EOF ;

/** A TCTL query (a <formula> element). */
queryText : query? EOF ;

/** A .q file: queries one after another. */
queriesFile : query* EOF ;

/** A TRON interface file (.trn). */
trnFile : trnItem* EOF ;

trnItem
    : kind=('input' | 'output') trnChannel (',' trnChannel)* ';'    # TrnChannels
    | 'precision' NAT ';'                                           # TrnPrecision
    | 'timeout' NAT ';'                                             # TrnTimeout
    ;

trnChannel : identifier ('(' (identifier (',' identifier)*)? ')')? ;

// ---------------------------------------------------------------- top level

topItem
    : declaration
    | processDecl
    | instantiation
    | ganttDecl
    ;

declaration
    : variableDecl
    | typedefDecl
    | functionDecl
    | chanPriorityDecl
    | oldConstDecl
    | dynamicDecl
    | importDecl
    ;

variableDecl : type variableDeclarator (',' variableDeclarator)* ';' ;

variableDeclarator : identifier arrayDim* ('=' initialiser | ':=' initialiser)? ;

arrayDim : '[' (expression | type) ']' ;

initialiser
    : expression
    | '{' initialiser (',' initialiser)* '}'
    ;

typedefDecl : 'typedef' type typedefName (',' typedefName)* ';' ;

typedefName : identifier arrayDim* ;

functionDecl : type identifier '(' parameterList? ')' block ;

parameterList : parameter (',' parameter)* ;

parameter : type ref='&'? identifier arrayDim* ;

chanPriorityDecl : 'chan' 'priority' chanPriorityItem (separators+=(',' | '<') chanPriorityItem)* ';' ;

/** A channel, possibly indexed; not an expression, so that {@code a < b} separates two levels. */
chanPriorityItem
    : 'default'
    | identifier ('[' expression ']')*
    ;

/** Statistical model checking: {@code dynamic T(int a);} declares a template that processes spawn. */
dynamicDecl : 'dynamic' identifier '(' parameterList? ')' ';' ;

/** Statistical model checking: {@code import "lib.so" { int f(int a); };} declares external functions. */
importDecl : 'import' STRING '{' importFunction* '}' ';'? ;

/**
 * {@code int f(int a);}, or {@code name = int f(int a);} (Uppaal 5's documented form) to call the library's {@code f}
 * {@code name} in the model; the older {@code int f(int a) = c_f;} is read too.
 */
importFunction : (alias=identifier '=')? type identifier '(' (importParameter (',' importParameter)*)? ')'
                 ('=' identifier)? ';' ;

importParameter : type ref='&'? identifier? arrayDim* ;

/** Uppaal 3: {@code const N 5;} */
oldConstDecl : 'const' oldConstItem (',' oldConstItem)* ';' ;

oldConstItem : identifier sign='-'? NAT ;

// ---------------------------------------------------------------- types

type : typePrefix* typeId ;

typePrefix : 'const' | 'urgent' | 'broadcast' | 'meta' | 'hybrid' ;

typeId
    : 'int' ('[' lower=expression ',' upper=expression ']')?   # IntType
    | 'bool'                                                   # BoolType
    | 'clock'                                                  # ClockType
    | 'chan'                                                   # ChanType
    | 'double'                                                 # DoubleType
    | 'void'                                                   # VoidType
    | 'scalar' '[' expression ']'                              # ScalarType
    | 'struct' '{' fieldDecl+ '}'                              # StructType
    | ID                                                       # NamedType
    ;

fieldDecl : type fieldDeclarator (',' fieldDeclarator)* ';' ;

fieldDeclarator : identifier arrayDim* ;

// ---------------------------------------------------------------- templates in XTA syntax

processDecl : 'process' identifier ('(' parameterList? ')')? '{' processBody '}' ;

processBody
    : declaration*
      stateDecl?
      (commitDecl | urgentDecl | branchpointDecl)*
      initDecl?
      transDecl?
    ;

stateDecl : 'state' locationDecl (',' locationDecl)* ';' ;

locationDecl : identifier ('{' guardExpr? '}')? ;

commitDecl : 'commit' identifier (',' identifier)* ';' ;

urgentDecl : 'urgent' identifier (',' identifier)* ';' ;

branchpointDecl : 'branchpoint' identifier (',' identifier)* ';' ;

initDecl : 'init' identifier ';' ;

transDecl : 'trans' transition (',' transition)* ';' ;

transition : (source=identifier)? '->' target=identifier '{' transitionBody '}' ;

transitionBody
    : ('select' selectItem (',' selectItem)* ';')?
      ('guard' guardExpr (',' guardExpr)* ';')?
      ('sync' syncExpr ';')?
      ('assign' expressionList? ';')?
    ;

syncExpr : expression direction=('!' | '?')? ;

selectItem : identifier ':' type ;

// ---------------------------------------------------------------- the system definition

instantiation
    : identifier ('(' parameterList? ')')? ('=' | ':=') template=identifier '(' argumentList? ')' ';'
    ;

systemLine : 'system' systemItem (separators+=(',' | '<') systemItem)* ';' ;

systemItem : identifier ;

trailer
    : ioDecl
    | progressDecl
    | ganttDecl
    ;

/** Uppaal's Gantt chart definitions: read and ignored (they only draw charts in Uppaal's simulator). */
ganttDecl : 'gantt' '{' ganttItem* '}' ;

ganttItem : identifier ('(' selectItem (',' selectItem)* ')')? ':' ganttMap (',' ganttMap)* ';' ;

ganttMap : ('for' '(' selectItem (',' selectItem)* ')')? expression '->' expression ;

/** ECDAR-style IO declarations, accepted and ignored. */
ioDecl : 'IO' identifier '{' syncExpr (',' syncExpr)* '}' ;

progressDecl : 'progress' '{' (expression (':' expression)? ';')* '}' ;

// ---------------------------------------------------------------- statements

block : '{' declaration* statement* '}' ;

statement
    : block                                                                    # BlockStatement
    | ';'                                                                      # EmptyStatement
    | expression ';'                                                           # ExpressionStatement
    | 'for' '(' init=expressionList? ';' cond=expression? ';' step=expressionList? ')' statement # ForStatement
    | 'for' '(' identifier ':' type ')' statement                              # IterationStatement
    | 'while' '(' expression ')' statement                                     # WhileStatement
    | 'do' statement 'while' '(' expression ')' ';'                            # DoWhileStatement
    | 'if' '(' expression ')' thenPart=statement ('else' elsePart=statement)?  # IfStatement
    | 'return' expression? ';'                                                 # ReturnStatement
    | 'break' ';'                                                              # BreakStatement
    | 'continue' ';'                                                           # ContinueStatement
    | 'assert' expression ';'                                                  # AssertStatement
    ;

// ---------------------------------------------------------------- expressions

expressionList : expression (',' expression)* ;

argumentList : expression (',' expression)* ;

/** A guard or invariant; old syntax allows comma-separated conjunctions only in process bodies. */
guardExpr : expression ;

expression
    : primary                                                                       # PrimaryExpr
    | expression '[' expression ']'                                                 # IndexExpr
    | expression '.' identifier                                                     # FieldExpr
    | expression '(' argumentList? ')'                                              # CallExpr
    | expression op=('++' | '--')                                                   # PostfixExpr
    | expression '\''                                                               # PrimeExpr
    | <assoc=right> op=('++' | '--' | '-' | '+' | '!') expression                   # PrefixExpr
    | <assoc=right> expression op='**' expression                                   # BinaryExpr
    | expression op=('*' | '/' | '%') expression                                    # BinaryExpr
    | expression op=('+' | '-') expression                                          # BinaryExpr
    | expression op=('<<' | '>>') expression                                        # BinaryExpr
    | expression op=('<?' | '>?') expression                                        # BinaryExpr
    | expression op=('<' | '<=' | '>=' | '>') expression                            # BinaryExpr
    | expression op=('==' | '!=') expression                                        # BinaryExpr
    | expression op='&' expression                                                  # BinaryExpr
    | expression op='^' expression                                                  # BinaryExpr
    | expression op='|' expression                                                  # BinaryExpr
    | expression op='&&' expression                                                 # BinaryExpr
    | expression op='||' expression                                                 # BinaryExpr
    | <assoc=right> expression '?' expression ':' expression                        # ConditionalExpr
    | <assoc=right> expression op=('=' | ':=' | '+=' | '-=' | '*=' | '/=' | '%=' | '|=' | '&=' | '^=' | '<<=' | '>>=') expression # AssignExpr
    | <assoc=right> op='not' expression                                             # PrefixExpr
    | expression op='and' expression                                                # BinaryExpr
    | expression op='or' expression                                                 # BinaryExpr
    | expression op='imply' expression                                              # BinaryExpr
    | <assoc=right> quantifier=('forall' | 'exists' | 'sum') '(' identifier ':' type ')' expression # QuantifierExpr
    ;

primary
    : NAT                           # NatLiteral
    | FLOAT                         # FloatLiteral
    | STRING                        # StringLiteral
    | 'true'                        # TrueLiteral
    | 'false'                       # FalseLiteral
    | 'deadlock'                    # DeadlockLiteral
    | 'spawn' identifier '(' argumentList? ')' # SpawnExpr
    | identifier                    # IdentifierRef
    | '(' expression ')'            # ParenExpr
    ;

// ---------------------------------------------------------------- queries

/** A query of Uppaal's verifier, optionally under a strategy. */
query : queryFormula ('under' strategy=identifier)? ;

queryFormula
    : E_EVENTUALLY expression                                                       # ExistsEventually
    | A_GLOBALLY expression                                                         # AlwaysGlobally
    | A_EVENTUALLY expression                                                       # AlwaysEventually
    | E_GLOBALLY expression                                                         # ExistsGlobally
    | expression '-->' expression                                                   # LeadsTo
    | kind=('sup' | 'inf' | 'bounds') ('{' expression '}')? ':' expressionList      # ValueBounds
    | 'control' ':' queryFormula                                                    # Control
    | 'control_t' '*' ('(' expressionList ')')? ':' queryFormula                    # Control
    | 'strategy' identifier '=' query                                               # StrategyDef
    | 'sat' ':' expression                                                          # Scenario
    | 'simulate' runs=expression? '[' runBound ']' '{' expressionList? '}' (':' expression (':' expression)?)? # Simulate
    | probability (op=('<=' | '>=' | '<' | '>') (probability | expression))?        # ProbabilityQuery
    | e=ID '[' runBound ']' '(' aggregate=identifier ':' expression ')'             # Expectation
    | kind=('minE' | 'maxE') '(' expression ')' '[' runBound ']'
      ('{' expressionList? '}' '->' '{' expressionList? '}')? ':' pathFormula       # Optimise
    | 'saveStrategy' '(' STRING ',' identifier ')'                                  # SaveStrategy
    | 'loadStrategy' ('{' expressionList? '}' '->' '{' expressionList? '}')? '(' STRING ')' # LoadStrategy
    ;

/** The bound of a run: {@code <=100}, {@code x<=100}, {@code #<=10}, and the number of runs after {@code ;}. */
runBound : ('#' | identifier)? '<=' expression (';' expression)? ;

probability : 'Pr' '[' runBound ']' '(' pathFormula ')' ;

pathFormula
    : '<' '>' expression
    | '[' ']' expression
    ;

// ---------------------------------------------------------------- identifiers

/** Names; the keywords of XTA process bodies are names everywhere else. */
identifier
    : ID
    | 'state' | 'init' | 'trans' | 'commit' | 'branchpoint'
    | 'guard' | 'sync' | 'assign' | 'select' | 'priority' | 'progress' | 'IO'
    | 'input' | 'output' | 'precision' | 'timeout'
    | 'gantt' | 'dynamic' | 'spawn' | 'import'
    | 'simulate' | 'Pr' | 'sup' | 'inf' | 'bounds' | 'control' | 'control_t' | 'strategy' | 'under' | 'sat'
    | 'minE' | 'maxE' | 'saveStrategy' | 'loadStrategy'
    ;

// ---------------------------------------------------------------- lexer

E_EVENTUALLY : 'E' [ \t]* '<>' ;
A_GLOBALLY : 'A' [ \t]* '[' [ \t]* ']' ;
A_EVENTUALLY : 'A' [ \t]* '<>' ;
E_GLOBALLY : 'E' [ \t]* '[' [ \t]* ']' ;

NAT : [0-9]+ ;
FLOAT : [0-9]+ '.' [0-9]+ ([eE] [+-]? [0-9]+)? | [0-9]+ [eE] [+-]? [0-9]+ ;
ID : [a-zA-Z_] [a-zA-Z_0-9]* ;
STRING : '"' (~["\\\r\n] | '\\' .)* '"' ;

LINE_COMMENT : '//' ~[\r\n]* -> skip ;
BLOCK_COMMENT : '/*' .*? '*/' -> skip ;

/** A comment that runs to the end of the text: reported by the parser. */
UNTERMINATED_COMMENT : '/*' ( ~'*' | '*'+ ~[*/] )* '*'* EOF ;
WS : [ \t\r\n\f\u00a0]+ -> skip ;

/** Anything else: reported by the parser as an unexpected character. */
UNEXPECTED_CHAR : . ;
