pub mod corpus;
pub mod seeded;
pub mod shapes;
pub mod worked;
